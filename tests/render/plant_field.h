#pragma once
// A flat field for the plant render tests: a 400 m plane coloured by one imagery layer of a
// species' reference colour, and seed triangles (two per 3 m square) from 30 m west to 30 m east
// and 5 … 62 m north of the origin; renders with and without plants for comparison.

#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/hash.h"
#include "gpu_test_fixture.h"
#include "tests/support/plant_field_scene.h"
#include "vegetation/colour_score.h"
#include "vegetation/species_catalog.h"

namespace vegstream::render::testing {

inline constexpr uint32_t kW = 320, kH = 180;
struct FieldResult {
  FrameResult with, without;
};

struct FieldView {
  glm::dvec3 position{0.0, 0.0, 2.0};
  glm::dvec3 forward{0.0, 1.0, -0.35};
  glm::dvec3 sun = Lighting{}.sunDirection;  // towards the sun
};

// The field coloured like `referenceOf`, rendered with `plants` and without.
inline FieldResult renderField(Renderer& r, const std::string& referenceOf, PlantStyle style,
                               const PlantDrawOptions& plantDraw = {}, const FieldView& view = {},
                               float plantCount = 40.0f) {
  {
    const std::array<uint8_t, 3> c = referenceColour(referenceOf);
    const std::vector<uint8_t> tile = flatTile(c[0], c[1], c[2]);
    const ImageryUpload upload{0, tile};
    terrain::TerrainMesh plane = flatPlane(kField, 8, 0.0f);
    for (auto& v : plane.vertices) v.uv = fieldUv(v.position.x, v.position.y);
    TerrainDraw draw{&plane};
    draw.imageryLayer = 0;
    FrameRequest req;
    req.lighting.exposureEv = 13.0f;  // fixed: frames are compared with each other pixel by pixel
    req.camera.position = view.position;
    req.camera.forward = glm::normalize(view.forward);
    req.camera.up = std::abs(req.camera.forward.z) > 0.99 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(0.0, 0.0, 1.0);
    req.cameraHeightMsl = view.position.z;
    req.lighting.sunDirection = view.sun;
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

// The grass field with plants alone, one frame (the frame a test then reads back, e.g.
// Renderer::readBladeVertices): the camera at `camera` looking along kFieldForward; `adjust` may
// change the seed triangles first (their eq. 1 counts, say).
inline const glm::dvec3 kFieldForward = glm::normalize(glm::dvec3(0.0, 1.0, -0.35));
inline bool renderPlantsFrame(Renderer& r, const PlantDrawOptions& plantDraw, const glm::dvec3& camera,
                              const std::function<void(std::vector<SeedTriangleGpu>&)>& adjust = {}) {
  const std::array<uint8_t, 3> c = referenceColour("grass");
  const std::vector<uint8_t> tile = flatTile(c[0], c[1], c[2]);
  const ImageryUpload upload{0, tile};
  terrain::TerrainMesh plane = flatPlane(kField, 8, 0.0f);
  for (auto& v : plane.vertices) v.uv = fieldUv(v.position.x, v.position.y);
  TerrainDraw draw{&plane};
  draw.imageryLayer = 0;
  FrameRequest req;
  req.lighting.exposureEv = 13.0f;  // fixed: frames are compared with each other pixel by pixel
  req.camera.position = camera;
  req.camera.forward = kFieldForward;
  req.camera.up = {0.0, 0.0, 1.0};
  req.cameraHeightMsl = camera.z;
  req.terrain = {&draw, 1};
  req.imageryUploads = {&upload, 1};
  std::vector<SeedTriangleGpu> seeds = seedTriangles(camera, 40.0f);
  if (adjust) adjust(seeds);
  VegetationRequest plants{seeds, 8, PlantStyle::Plants, plantDraw};
  req.vegetation = &plants;
  return r.renderFrame(req).ok();
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
