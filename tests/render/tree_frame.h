#pragma once
// One frame of the trees' render tests (tree_render_test.cpp, tree_shadow_test.cpp): the given
// trees in one page over one terrain draw, full models at every distance, at a fixed exposure so
// frames compare pixel by pixel, colour and depth read back; a test failure and an empty result
// when the renderer fails.

#include <cstdint>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.h"

namespace vegstream::render::testing {

// withTrees false: the same frame without trees; upload: the imagery to upload first, or null;
// nearFadeM: TreeLodDistances::nearFadeM; modelHeights: where the models end and the impostors
// begin, in tree heights (the full model at every distance unless set; 0: impostors only).
inline FrameResult renderTreeFrame(Renderer& r, const Camera& camera, const glm::dvec3& sun, const TerrainDraw& draw,
                                   const ImageryUpload* upload, std::span<const TreeInstanceGpu> trees, bool withTrees,
                                   bool shadows, float nearFadeM = TreeLodDistances{}.nearFadeM,
                                   float modelHeights = 1e6f) {
  FrameRequest req;
  req.lighting.exposureEv = 13.0f;  // fixed: frames are compared with each other pixel by pixel
  req.camera = camera;
  req.cameraHeightMsl = camera.position.z;
  req.lighting.sunDirection = sun;
  req.readbackColor = req.readbackDepth = true;
  req.terrain = {&draw, 1};
  if (upload) req.imageryUploads = {upload, 1};
  const std::vector<TreePageUpload> uploads = {{0, static_cast<uint32_t>(trees.size()), trees.data()}};
  const std::vector<uint32_t> counts = {static_cast<uint32_t>(trees.size())};
  TreeRequest t;
  t.uploads = uploads;
  t.pageCounts = counts;
  t.shadows = shadows;
  t.lod.fullHeights = t.lod.reducedHeights = modelHeights;
  t.lod.nearFadeM = nearFadeM;
  t.cameraEnu[0] = camera.position.x, t.cameraEnu[1] = camera.position.y, t.cameraEnu[2] = camera.position.z;
  if (withTrees) req.trees = &t;
  auto f = r.renderFrame(req);
  EXPECT_TRUE(f.ok());
  return f.ok() ? std::move(*f) : FrameResult{};
}

}  // namespace vegstream::render::testing
