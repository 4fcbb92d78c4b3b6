// Imagery sampling shared by the CPU reference and the classify pass (see the header).
#include "vegetation/imagery_texels.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/common.hpp>

#include "vegetation/colour_score.h"

namespace vegstream::vegetation {
namespace {

glm::vec3 texel(const ImageryTexels& t, int x, int y) {
  const int last = static_cast<int>(t.size) - 1;
  x = std::clamp(x, 0, last);
  y = std::clamp(y, 0, last);
  const uint8_t* p = t.rgba + (static_cast<size_t>(y) * t.size + static_cast<size_t>(x)) * 4;
  return {srgbDecode(p[0] / 255.0f), srgbDecode(p[1] / 255.0f), srgbDecode(p[2] / 255.0f)};
}

}  // namespace

float sampleImageryNdvi(const ImageryTexels& tile, glm::vec2 uv) {
  if (!tile.ndvi) return kNoNdvi;
  const float n = static_cast<float>(tile.size);
  const float x = uv.x * n - 0.5f, y = uv.y * n - 0.5f;
  const float fx0 = std::floor(x), fy0 = std::floor(y);
  const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
  const float fx = x - fx0, fy = y - fy0;
  const int last = static_cast<int>(tile.size) - 1;
  float sum = 0.0f, weight = 0.0f;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int tx = std::clamp(x0 + i, 0, last), ty = std::clamp(y0 + j, 0, last);
      const uint8_t b = tile.ndvi[static_cast<size_t>(ty) * tile.size + static_cast<size_t>(tx)];
      if (b == 0) continue;
      const float w = (i == 1 ? fx : 1.0f - fx) * (j == 1 ? fy : 1.0f - fy);
      sum += w * ((static_cast<float>(b) - 128.0f) / 127.0f);
      weight += w;
    }
  return weight > 0.0f ? sum / weight : kNoNdvi;
}

glm::vec3 sampleImageryLinear(const ImageryTexels& tile, glm::vec2 uv) {
  assert(tile.rgba && tile.size > 0);
  const float n = static_cast<float>(tile.size);
  const float x = uv.x * n - 0.5f, y = uv.y * n - 0.5f;
  const float fx0 = std::floor(x), fy0 = std::floor(y);
  const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
  const float fx = x - fx0, fy = y - fy0;
  const glm::vec3 top = glm::mix(texel(tile, x0, y0), texel(tile, x0 + 1, y0), fx);
  const glm::vec3 bottom = glm::mix(texel(tile, x0, y0 + 1), texel(tile, x0 + 1, y0 + 1), fx);
  return glm::mix(top, bottom, fy);
}

}  // namespace vegstream::vegetation
