#version 450
#extension GL_GOOGLE_include_directive : require
// Test kernel, not a pass: evaluates common/species_choice.glsl's chooseSpeciesAllowed (core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 eq. 16–18, restricted to the species a landcover
// class allows, issue 41) for a list of inputs so tests/render/landcover_choice_gpu_test.cpp can
// compare it with vegetation/species_choice.h. Set 0: binding 0 the catalog block as classify.comp
// reads it, 1 the inputs, 2 the results.
#include "colour_score.glsl"
#include "classify_layout.glsl"

layout(set = 0, binding = 0, std140) uniform SpeciesBlock {
  Species species[kMaxSpecies];
  uvec4 speciesCount;
} catalog;

#include "species_choice.glsl"

layout(local_size_x = 64) in;
struct ChoiceInput {
  vec4 hsvNdvi;  // xyz: HSV, w: NDVI (kNoNdvi: none)
  uvec4 zAllowed;  // x: z as float bits, y: the allowed-species mask
};
layout(set = 0, binding = 1, std430) readonly buffer Inputs { ChoiceInput inputs[]; };
layout(set = 0, binding = 2, std430) writeonly buffer Outputs { vec2 results[]; };  // (species, s′)
layout(push_constant) uniform Push {
  uint count;
} push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  ChoiceInput c = inputs[i];
  results[i] = chooseSpeciesAllowed(vec4(c.hsvNdvi.xyz, -2.0 /* kNoExg: no ExG term */), c.hsvNdvi.w, uintBitsToFloat(c.zAllowed.x), c.zAllowed.y);
}
