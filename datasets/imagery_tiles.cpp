// Imagery tiles of the max zoom: sampled, de-shaded, sRGB-encoded (imagery_tiles.h).

#include "datasets/imagery_tiles.h"

#include <algorithm>
#include <cmath>

#include "datasets/srgb.h"

namespace vegstream::datasets {
namespace {

constexpr int kGroupBlock = 64;  // pixels on a side of one sun-estimate group

// The colour sampled at p in linear light; false where there is none.
bool linearColour(const ImageryTiling& t, const Raster& window, glm::dvec2 p, glm::vec3& out) {
  std::array<float, 3> v{};
  if (!sampleColour(window, p, v)) return false;
  for (int c = 0; c < 3; ++c)
    out[c] =
        t.linear ? std::clamp(v[static_cast<size_t>(c)], 0.0f, 1.0f) : srgbDecode(v[static_cast<size_t>(c)] / 255.0f);
  return true;
}

// Ground size of a pixel of tile `id` at its centre latitude.
double pixelMetres(const geo::TileId& id, int size) {
  const glm::dvec2 centre = geo::tileXYToLonLat({id.x + 0.5, id.y + 0.5}, id.z);
  return geo::groundResolution(centre.y, id.z, size);
}

}  // namespace

bool fillImageryTile(const ImageryTiling& t, const TileImagery& img, const std::vector<float>& heights, ColorTile& c) {
  const std::vector<glm::dvec2>& imgPx = img.px;
  const int size = c.size;
  c.rgba.assign(imgPx.size() * 4, 0);
  std::vector<glm::vec3> normals;
  if (t.sun) normals = tileNormals(heights, size, pixelMetres(c.id, size));
  bool any = false;
  for (size_t i = 0; i < imgPx.size(); ++i) {
    uint8_t* px = &c.rgba[i * 4];
    if (!t.linear && !t.sun) {  // display or sRGB bytes as they are
      std::array<float, 3> v{};
      if (!sampleColour(img.window, imgPx[i], v)) continue;
      for (size_t ch = 0; ch < 3; ++ch) px[ch] = static_cast<uint8_t>(std::lround(std::clamp(v[ch], 0.f, 255.f)));
    } else {
      glm::vec3 lin;
      if (!linearColour(t, img.window, imgPx[i], lin)) continue;
      if (t.sun) lin *= deshadingGain(glm::dvec3(normals[i]), *t.sun, t.directFraction);
      for (int ch = 0; ch < 3; ++ch) px[ch] = srgbEncode8(lin[ch]);
    }
    px[3] = 255;
    any = true;
  }
  return any;
}

std::vector<ShadingSample> collectShadingSamples(
    const ImageryTiling& t, const std::vector<geo::TileId>& tiles, int size,
    const std::function<std::vector<float>(const geo::TileId&)>& heightsOf,
    const std::function<std::optional<TileImagery>(const geo::TileId&)>& imageryOf, size_t maxSamples) {
  std::vector<ShadingSample> samples;
  const size_t step = std::max<size_t>(1, tiles.size() / 64);
  const int blocks = (size + kGroupBlock - 1) / kGroupBlock;
  uint32_t groupBase = 0;
  for (size_t k = 0; k < tiles.size(); k += step, groupBase += static_cast<uint32_t>(blocks * blocks)) {
    const geo::TileId& id = tiles[k];
    const std::optional<TileImagery> img = imageryOf(id);
    if (!img) continue;
    const std::vector<float> heights = heightsOf(id);
    const std::vector<glm::vec3> normals = tileNormals(heights, size, pixelMetres(id, size));
    const std::vector<glm::dvec2>& px = img->px;
    for (int j = 0; j < size; j += 2)
      for (int i = 0; i < size; i += 2) {
        const size_t at = static_cast<size_t>(j) * static_cast<size_t>(size) + static_cast<size_t>(i);
        glm::vec3 lin;
        if (!std::isfinite(heights[at]) || !linearColour(t, img->window, px[at], lin)) continue;
        const float y = 0.2126f * lin.r + 0.7152f * lin.g + 0.0722f * lin.b;
        if (!(y > 1e-3f)) continue;
        const auto group = groupBase + static_cast<uint32_t>((j / kGroupBlock) * blocks + i / kGroupBlock);
        samples.push_back({normals[at], std::log(y), group});
      }
  }
  if (samples.size() > maxSamples) {  // every n-th, keeping the spread
    const double keep = static_cast<double>(samples.size()) / static_cast<double>(maxSamples);
    std::vector<ShadingSample> thin;
    thin.reserve(maxSamples);
    for (size_t n = 0; n < maxSamples; ++n) thin.push_back(samples[static_cast<size_t>(static_cast<double>(n) * keep)]);
    samples.swap(thin);
  }
  // Dense group numbers: estimateSun sizes its sums by the largest.
  std::vector<uint32_t> dense(groupBase, UINT32_MAX);
  uint32_t next = 0;
  for (auto& s : samples) {
    if (dense[s.group] == UINT32_MAX) dense[s.group] = next++;
    s.group = dense[s.group];
  }
  return samples;
}

}  // namespace vegstream::datasets
