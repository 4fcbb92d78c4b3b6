#pragma once
// What the frame's CPU stages (streaming, terrain, seeding, trees) cost and did in one frame: the
// producers' own figures kept whole, and the stages' times. The stages fill it in the frame's
// context (frame_context.h); the record keeps it (frame_driver.h), the stages' figure
// declarations read it.

#include <cstdint>
#include <optional>

#include "scene/tree_field_figures.h"
#include "streaming/tile_streamer.h"
#include "terrain/streamed_terrain.h"

namespace vegstream::scene {

// What one frame cost and did, for the recorder and the HUD.
struct SceneFrameFigures {
  double streamingMs = 0.0;   // update + upload planning, CPU (settle wait excluded)
  double settleWaitMs = 0.0;  // settled mode: waiting for wanted tiles (left out of frame time)
  double terrainMs = 0.0;     // selection, wants, pieces (mesh builds included)
  streaming::StreamingFrameStats streaming;
  terrain::TerrainFrameFigures terrain;
  uint64_t uploads = 0;                  // imagery tiles uploaded this frame
  uint64_t cpuBytes = 0;                 // resident tiles + ground mosaic
  uint64_t gpuBytes = 0;                 // imagery array, terrain, classify and plant buffers
  uint64_t seedTrianglesClassified = 0;  // seed triangles with imagery, sent to the classify pass
  double seedingMs = 0.0;                // making them ready for the GPU (keys, camera-relative)
  // Trees: tiles placed and given pages this frame (scene/tree_field.h); absent without trees.
  std::optional<TreeFieldFigures> trees;
  uint64_t treeGpuBytes = 0;  // the renderer's tree pool
};

}  // namespace vegstream::scene
