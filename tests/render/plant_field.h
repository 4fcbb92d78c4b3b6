#pragma once
// A flat field for the plant render tests: a 400 m plane coloured by one imagery layer of a
// species' reference colour, and seed triangles (two per 3 m square) from 30 m west to 30 m east
// and 5 … 62 m north of the origin; renders with and without plants for comparison.

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/hash.h"
#include "gpu_test_fixture.h"
#include "vegetation/colour_score.h"
#include "vegetation/species_catalog.h"

namespace vegstream::render::testing {

inline constexpr uint32_t kW = 320, kH = 180;
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

// The two right triangles of each 3 m square from 30 m west to 30 m east and 5 … 62 m north,
// camera-relative.
inline std::vector<SeedTriangleGpu> seedTriangles(const glm::dvec3& camera, float plants) {
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
    ++i;
    out.push_back(t);
  };
  for (double y = 5.0; y < 60.0; y += 3.0)
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
    const glm::vec3 hsv = s.score.reference;
    const float h6 = hsv.x * 6.0f, c = hsv.z * hsv.y, x = c * (1.0f - std::abs(std::fmod(h6, 2.0f) - 1.0f));
    const glm::vec3 sectors[] = {{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}};
    const glm::vec3 rgb = sectors[static_cast<int>(h6) % 6] + (hsv.z - c);
    return {static_cast<uint8_t>(std::lround(rgb.r * 255.0f)), static_cast<uint8_t>(std::lround(rgb.g * 255.0f)),
            static_cast<uint8_t>(std::lround(rgb.b * 255.0f))};
  }
  ADD_FAILURE() << "no species " << name;
  return {0, 0, 0};
}

inline int speciesIndex(const std::string& name) {
  const auto& s = vegetation::defaultSpeciesCatalog().species;
  for (size_t i = 0; i < s.size(); ++i)
    if (s[i].name == name) return static_cast<int>(i);
  return -1;
}

struct FieldResult {
  FrameResult with, without;
};

struct FieldView {
  glm::dvec3 position{0.0, 0.0, 2.0};
  glm::dvec3 forward{0.0, 1.0, -0.35};
};

// The field coloured like `referenceOf`, rendered with `plants` and without.
inline FieldResult renderField(Renderer& r, const std::string& referenceOf, PlantStyle style,
                               const PlantDrawOptions& plantDraw = {}, const FieldView& view = {}, float plantCount = 40.0f) {
  {
    const std::array<uint8_t, 3> c = referenceColour(referenceOf);
    const std::vector<uint8_t> tile = flatTile(c[0], c[1], c[2]);
    const ImageryUpload upload{0, tile.data()};
    terrain::TerrainMesh plane = flatPlane(kField, 8, 0.0f);
    for (auto& v : plane.vertices) v.uv = fieldUv(v.position.x, v.position.y);
    TerrainDraw draw{&plane};
    draw.imageryLayer = 0;
    FrameRequest req;
    req.camera.position = view.position;
    req.camera.forward = glm::normalize(view.forward);
    req.camera.up = std::abs(req.camera.forward.z) > 0.99 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(0.0, 0.0, 1.0);
    req.cameraHeightMsl = view.position.z;
    req.readbackColor = true;
    req.terrain = {&draw, 1};
    req.imageryUploads = {&upload, 1};
    const std::vector<SeedTriangleGpu> seeds = seedTriangles(req.camera.position, plantCount);
    VegetationRequest plants{seeds, 8, style, plantDraw};
    req.vegetation = &plants;
    auto with = r.renderFrame(req);
    EXPECT_TRUE(with.ok());
    req.vegetation = nullptr;
    req.imageryUploads = {};
    auto without = r.renderFrame(req);
    EXPECT_TRUE(without.ok());
    return {std::move(*with), std::move(*without)};
  }
}

// Pixels that differ between the two frames by more than `threshold` (8-bit sRGB, any channel),
// in rows [y0, y1).
inline size_t changedPixels(const ColorImage& a, const ColorImage& b, uint32_t y0, uint32_t y1, int threshold = 24) {
  size_t n = 0;
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = 0; x < a.width; ++x) {
      const size_t i = (size_t{y} * a.width + x) * 4;
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c])));
      if (d > threshold) ++n;
    }
  return n;
}

}  // namespace vegstream::render::testing
