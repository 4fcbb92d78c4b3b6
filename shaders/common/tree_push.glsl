#ifndef TREE_PUSH_GLSL
#define TREE_PUSH_GLSL
// The tree pipelines' push constants (render/tree_pass.cpp TreePush mirrors them).
const int kTreeMaxChain = 4;  // vegetation::kMaxBranchLevels + 1: the trunk and its descendants
layout(push_constant) uniform TreePush {
  mat4 capture;  // mode 1: the light's (shadow cascade's) view-projection
  uint model;
  uint lod;      // impostor capture: the views per side
  uint mode;     // 0 colour, 1 shadow depth, 2 impostor capture (albedo + coverage, normal + depth)
  uint samples;  // MSAA samples of the target (alpha to coverage)
} push;
mat4 treeShadowMatrix(uint cascade) { return push.capture; }
#ifdef SIMULATION_BLOCK_GLSL
// The shared simulation's time at the end of this frame's steps: the wind's clock.
float treeTime() { return sim.clock.y + sim.clock.x * sim.clock.z; }
#endif
#endif
