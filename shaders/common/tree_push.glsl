#ifndef TREE_PUSH_GLSL
#define TREE_PUSH_GLSL
// The tree pipelines' push constants (render/tree_pass.cpp TreePush mirrors them).
const int kTreeMaxChain = 4;  // vegetation::kMaxBranchLevels + 1: the trunk and its descendants
layout(push_constant) uniform TreePush {
  mat4 capture;  // mode 1: the shadow cascade's view-projection (tree_shadow_raster.comp)
  uint model;
  uint lod;      // impostor capture: the views per side; mode 1: the cascade
  uint mode;     // 0 colour, 1 shadow cascade (compute), 2 impostor capture (albedo + coverage, normal + depth)
  uint samples;  // MSAA samples of the target (alpha to coverage)
} push;
#ifdef SIMULATION_BLOCK_GLSL
// The shared simulation's time at the end of this frame's steps: the wind's clock.
float treeTime() { return sim.clock.y + sim.clock.x * sim.clock.z; }
#endif
#endif
