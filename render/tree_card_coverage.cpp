// The cards' coverage texture (tree_card_coverage.h).
#include "render/tree_card_coverage.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>

namespace vegstream::render {
namespace {

// A size² level: the mean of n × n points spread evenly over each texel.
std::vector<float> pointLevel(uint32_t layer, uint32_t size, uint32_t n, float detail) {
  std::vector<float> level(size_t{size} * size);
  const float step = 1.0f / static_cast<float>(size * n);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      float sum = 0.0f;
      for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i)
          sum += treeCardOutline(layer, (static_cast<float>(x * n + i) + 0.5f) * step,
                                 (static_cast<float>(y * n + j) + 0.5f) * step, detail);
      level[size_t{y} * size + x] = sum / static_cast<float>(n * n);
    }
  return level;
}

// The level below `above` (side 2 × size): each texel the mean of the four it covers.
std::vector<float> boxLevel(const std::vector<float>& above, uint32_t size) {
  assert(above.size() == size_t{4} * size * size);
  std::vector<float> level(size_t{size} * size);
  const size_t row = size_t{2} * size;
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      const size_t a = (size_t{2} * y) * row + size_t{2} * x;
      level[size_t{y} * size + x] = 0.25f * (above[a] + above[a + 1] + above[a + row] + above[a + row + 1]);
    }
  return level;
}

// Every level of every layer as R8 texels, in the order recordImageArrayUpload reads them.
std::vector<uint8_t> texelBytes() {
  std::vector<uint8_t> bytes;
  for (uint32_t layer = 0; layer < kTreeCardLayers; ++layer)
    for (const std::vector<float>& level : bakeTreeCardLayer(layer))
      for (float c : level) bytes.push_back(static_cast<uint8_t>(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f)));
  return bytes;
}

}  // namespace

float treeCardOutline(uint32_t layer, float u, float v, float detail) {
  const glm::vec2 uv(u, v);
  return layer == 0 ? card_shape::coniferNeedlesAt(uv, detail) : card_shape::broadleafClumpAt(uv);
}

float treeCardLevelDetail(uint32_t level) {
  const auto texelsPerPixel = static_cast<float>(1u << kTreeCardFinerLevels);
  const float texel = 1.0f / static_cast<float>(kTreeCardSize >> level);  // a level-`level` texel's side in uv
  return card_shape::needleDetail(card_shape::needleRowsAcross(texel, texel) * texelsPerPixel);
}

std::vector<std::vector<float>> bakeTreeCardLayer(uint32_t layer) {
  assert(layer < kTreeCardLayers);
  std::vector<std::vector<float>> levels;
  levels.push_back(pointLevel(layer, kTreeCardSize, 2, treeCardLevelDetail(0)));
  for (uint32_t level = 1; level < kTreeCardLevels; ++level) {
    const uint32_t size = kTreeCardSize >> level;
    // The broadleaf has no detail to fade; a conifer level whose needles are still drawn whole is
    // the box filter of the one above (which drew them whole too: the detail falls with the level).
    const bool whole = layer != 0 || treeCardLevelDetail(level) >= 1.0f;
    levels.push_back(whole ? boxLevel(levels.back(), size) : pointLevel(layer, size, 4, treeCardLevelDetail(level)));
  }
  return levels;
}

TreeCardCoverage::TreeCardCoverage(const Context& ctx) {
  image_ = createImageArray(ctx, {kTreeCardSize, kTreeCardSize}, kTreeCardLayers, VK_FORMAT_R8_UNORM,
                            VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "tree card coverage",
                            kTreeCardLevels);
  sampler_ = createTrilinearClampSampler(ctx, kTreeCardLevels, "tree card coverage sampler");
  const std::vector<uint8_t> bytes = texelBytes();
  GpuBuffer staging = createBuffer(ctx, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostUpload,
                                   "tree card coverage staging");
  std::memcpy(staging.mapped, bytes.data(), bytes.size());
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    const VkDeviceSize used = recordImageArrayUpload(cmd, staging, image_);
    assert(used == bytes.size());
    (void)used;
  });
}

}  // namespace vegstream::render
