#pragma once
// A flat field for the plant tests and benchmarks (no test framework here): a 400 m plane
// coloured by one imagery layer of a species' reference colour, and seed triangles (two per 3 m
// square) from 30 m west to 30 m east and 5 … 62 m north of the origin.

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/hash.h"
#include "render/classify_layout.h"
#include "render/frame_types.h"
#include "terrain/terrain_mesh.h"
#include "vegetation/colour_score.h"
#include "vegetation/plant_seeding.h"
#include "vegetation/species_catalog.h"

namespace vegstream::render::testing {

// A flat square of side `size` metres centred on the origin at height z, subdivided n × n,
// facing up (counter-clockwise seen from above).
inline terrain::TerrainMesh flatPlane(double size, int n, float z) {
  terrain::TerrainMesh mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = static_cast<float>(-0.5 * size + size * i / n);
      const float y = static_cast<float>(-0.5 * size + size * j / n);
      mesh.vertices.push_back({{x, y, z}, {0.0f, 0.0f, 1.0f}, 1500.0f});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto a = static_cast<uint32_t>(j * (n + 1) + i), b = a + 1;
      const auto c = static_cast<uint32_t>((j + 1) * (n + 1) + i), d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, c, b, d, c});
    }
  return mesh;
}

inline constexpr double kField = 400.0;  // metres, the plane and its one imagery tile

inline std::vector<uint8_t> flatTile(uint8_t r, uint8_t g, uint8_t b) {
  std::vector<uint8_t> rgba(size_t{kImageryTileSize} * kImageryTileSize * 4);
  for (size_t i = 0; i < rgba.size(); i += 4) {
    rgba[i] = r;
    rgba[i + 1] = g;
    rgba[i + 2] = b;
    rgba[i + 3] = 255;
  }
  return rgba;
}

inline glm::vec2 fieldUv(double x, double y) {
  return {static_cast<float>(x / kField + 0.5), static_cast<float>(0.5 - y / kField)};
}

// The two right triangles of each 3 m square from 30 m west to 30 m east and from 5 m north to
// the first row ending past `northM` (62 m by default), camera-relative.
inline std::vector<SeedTriangleGpu> seedTriangles(const glm::dvec3& camera, float plants, double northM = 60.0) {
  std::vector<SeedTriangleGpu> out;
  uint32_t i = 0;
  auto add = [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    SeedTriangleGpu t;
    t.v0 = glm::vec4(glm::vec3(a - camera), plants);
    t.v1 = glm::vec4(glm::vec3(b - camera), 0.0f);
    t.v2 = glm::vec4(glm::vec3(c - camera), 0.0f);
    t.uv01 = glm::vec4(fieldUv(a.x, a.y), fieldUv(b.x, b.y));
    t.uv2 = fieldUv(c.x, c.y);
    t.keyLo = mix32(2 * i + 11);
    t.keyHi = mix32(2 * i + 12);
    t.layer = 0;
    // Full detail at the camera: every species up to its density over the area (or `plants`).
    t.lodCount = std::numeric_limits<float>::infinity();
    t.areaM2 = vegetation::seedArea({a, b, c});
    ++i;
    out.push_back(t);
  };
  for (double y = 5.0; y < northM; y += 3.0)
    for (double x = -30.0; x < 30.0; x += 3.0) {
      add({x, y, 0.0}, {x + 3.0, y, 0.0}, {x, y + 3.0, 0.0});
      add({x + 3.0, y + 3.0, 0.0}, {x, y + 3.0, 0.0}, {x + 3.0, y, 0.0});
    }
  return out;
}

// The 8-bit sRGB of a species' reference colour (HSV hexcone → RGB).
inline std::array<uint8_t, 3> referenceColour(const std::string& name) {
  for (const vegetation::Species& s : vegetation::defaultSpeciesCatalog().species) {
    if (s.name != name) continue;
    const glm::vec3 rgb = vegetation::srgbFromHsv(s.score.reference);
    return {static_cast<uint8_t>(std::lround(rgb.r * 255.0f)), static_cast<uint8_t>(std::lround(rgb.g * 255.0f)),
            static_cast<uint8_t>(std::lround(rgb.b * 255.0f))};
  }
  return {0, 0, 0};  // no such species: black (callers check speciesIndex first)
}

inline int speciesIndex(const std::string& name) {
  const auto& s = vegetation::defaultSpeciesCatalog().species;
  for (size_t i = 0; i < s.size(); ++i)
    if (s[i].name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace vegstream::render::testing
