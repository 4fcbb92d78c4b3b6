#pragma once
// A synthetic classify workload shared by tests/render/classify_gpu_test.cpp and
// bench/bench_classify.cpp: 256 × 256 imagery tiles (1 m per texel) of meadow green, red rock and
// pale sandstone with texel noise, and seed triangles over them with plant counts spread
// log-uniformly from 0.3 to 256 (unclustered, fading and clustered triangles in many bins).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/hash.h"
#include "render/classify_layout.h"
#include "render/frame_types.h"
#include "vegetation/imagery_texels.h"
#include "vegetation/plant_seeding.h"

namespace vegstream::testing {

inline constexpr uint32_t kClassifyTile = render::kImageryTileSize;

// sRGB 8-bit tile: green meadow on the west, red rock in the middle, pale sandstone in the
// east, with texel noise so colours vary within each region.
inline std::vector<uint8_t> classifyBaseMap(uint32_t seed) {
  std::vector<uint8_t> rgba(size_t{kClassifyTile} * kClassifyTile * 4);
  for (uint32_t y = 0; y < kClassifyTile; ++y)
    for (uint32_t x = 0; x < kClassifyTile; ++x) {
      const uint32_t h = mix32(x * 7919u + y * 104729u + seed);
      const int n = static_cast<int>(h % 21u) - 10;
      int r = 90, g = 115, b = 55;                       // meadow green
      if (x > 100 && x <= 180) r = 150, g = 90, b = 70;  // red rock
      if (x > 180) r = 210, g = 198, b = 176;            // pale sandstone
      uint8_t* p = &rgba[(size_t{y} * kClassifyTile + x) * 4];
      p[0] = static_cast<uint8_t>(std::clamp(r + n, 0, 255));
      p[1] = static_cast<uint8_t>(std::clamp(g + n, 0, 255));
      p[2] = static_cast<uint8_t>(std::clamp(b + n, 0, 255));
      p[3] = 255;
    }
  return rgba;
}

struct ClassifyScene {
  std::vector<render::SeedTriangleGpu> gpu;
  std::vector<vegetation::SeedTriangleInput> cpu;
};

// Right triangles of 4 m legs every `spacing` metres over the tile, layers used in turn. With
// `imageryChanges` (and 2 or more layers), every 5th triangle's imagery is changing from the
// next layer's (a species cross-fade, blend 0.1 … 0.9) and every 7th's is fading in (no
// previous layer, blend 0.35).
inline ClassifyScene makeClassifyScene(uint32_t layers, float spacing = 9.0f, bool imageryChanges = false) {
  ClassifyScene s;
  uint32_t i = 0;
  for (float y = 2.0f; y < 250.0f; y += spacing)
    for (float x = 2.0f; x < 250.0f; x += spacing, ++i) {
      render::SeedTriangleGpu t;
      const float n = 0.3f * std::pow(256.0f / 0.3f, static_cast<float>(mix32(i) % 1000u) / 999.0f);
      t.v0 = {x, y, 10.0f, n};
      t.v1 = {x + 4.0f, y, 10.5f, 0.0f};
      t.v2 = {x, y + 4.0f, 9.5f, 0.0f};
      const float s256 = 1.0f / 256.0f;
      // Tile rows run north → south; the scene's y is northwards.
      t.uv01 = {x * s256, 1.0f - y * s256, (x + 4.0f) * s256, 1.0f - y * s256};
      t.uv2 = {x * s256, 1.0f - (y + 4.0f) * s256};
      t.keyLo = mix32(i * 2u + 1u);
      t.keyHi = mix32(i * 2u + 2u);
      t.layer = static_cast<int32_t>(i % layers);
      s.gpu.push_back(t);
      vegetation::SeedTriangleInput c;
      c.key = (uint64_t{t.keyHi} << 32) | t.keyLo;
      c.vertices = {glm::dvec3(glm::vec3(t.v0)), glm::dvec3(glm::vec3(t.v1)), glm::dvec3(glm::vec3(t.v2))};
      c.plantCount = n;
      // Full detail at the camera: each species' count is its density over the area (or N).
      s.gpu.back().lodCount = c.lodCount;
      s.gpu.back().areaM2 = vegetation::seedArea(c.vertices);
      if (imageryChanges && layers >= 2 && i % 5 == 0) {
        s.gpu.back().previousLayer = static_cast<int32_t>((i + 1) % layers);
        s.gpu.back().previousUv01 = t.uv01;
        s.gpu.back().previousUv2 = t.uv2;
        c.imageryBlend = s.gpu.back().imageryBlend = 0.1f + 0.8f * static_cast<float>(mix32(i ^ 77u) % 100u) / 99.0f;
      } else if (imageryChanges && i % 7 == 0) {
        c.imageryBlend = s.gpu.back().imageryBlend = 0.35f;
      }
      s.cpu.push_back(c);
    }
  return s;
}

// The CPU reference's colour lookup for triangle `t` of a scene over `maps` (one per layer).
inline vegetation::BaseColourAt classifyColour(const render::SeedTriangleGpu& t,
                                               const std::vector<std::vector<uint8_t>>& maps) {
  const vegetation::ImageryTexels texels{maps[size_t(t.layer)].data(), kClassifyTile};
  return [texels, t](glm::vec2 r) {
    const glm::vec2 uv0(t.uv01.x, t.uv01.y), uv1(t.uv01.z, t.uv01.w);
    return vegetation::sampleImageryLinear(texels, uv0 + r.x * (uv1 - uv0) + r.y * (t.uv2 - uv0));
  };
}

// The same for the imagery drawn before it (empty when it has none).
inline vegetation::BaseColourAt classifyPreviousColour(const render::SeedTriangleGpu& t,
                                                       const std::vector<std::vector<uint8_t>>& maps) {
  if (t.previousLayer < 0) return {};
  const vegetation::ImageryTexels texels{maps[size_t(t.previousLayer)].data(), kClassifyTile};
  return [texels, t](glm::vec2 r) {
    const glm::vec2 uv0(t.previousUv01.x, t.previousUv01.y), uv1(t.previousUv01.z, t.previousUv01.w);
    return vegetation::sampleImageryLinear(texels, uv0 + r.x * (uv1 - uv0) + r.y * (t.previousUv2 - uv0));
  };
}

}  // namespace vegstream::testing
