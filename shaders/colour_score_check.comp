#version 450
#extension GL_GOOGLE_include_directive : require
// Test kernel, not a pass: evaluates common/colour_score.glsl and common/terrain_detail.glsl for
// a list of colours so tests/render/colour_score_gpu_test.cpp can compare them with the C++
// (vegetation/colour_score.h, vegetation/terrain_types.h). Set 0: binding 1 the TerrainDetail
// block (as the terrain pass fills it), 2 the input colours, 3 the results.
#define TERRAIN_DETAIL_SET 0
#include "colour_score.glsl"
#include "terrain_detail.glsl"
#include "colour_calibration.glsl"
layout(local_size_x = 64) in;
layout(set = 0, binding = 2, std430) readonly buffer Inputs {
  vec4 linearRgb[];  // rgb: linear colour; a: unused
} inputs;
// Per colour, 8 vec4: HSV + the log score of type 0; type weights 0–3, 4–7, 8–11, 12–15;
// surface weights; calibratedGround (HSV, ExG) through `calibration`; the log score of type 0
// with its NDVI term off and the ExG term of `calibration.exg` on the calibrated colour.
layout(set = 0, binding = 3, std430) writeonly buffer Outputs {
  vec4 values[];
} outputs;
layout(set = 0, binding = 4, std140) uniform Calibration {
  vec4 rows[3];  // vegetation/colour_calibration.h
  vec4 exg;      // x: ExG reference, y: its weight
} calibration;
layout(push_constant) uniform Push {
  uint count;
} push;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  vec3 hsv = hsvFromLinear(inputs.linearRgb[i].rgb);
  float w[kMaxTerrainTypes];
  terrainTypeWeights(hsv, w);
  outputs.values[8 * i + 0] = vec4(hsv, logColourScore(detail.reference[0].xyz, detail.weights[0].xyz, detail.reference[0].w, hsv));
  for (int k = 0; k < 4; ++k) outputs.values[8 * i + 1 + k] = vec4(w[4 * k], w[4 * k + 1], w[4 * k + 2], w[4 * k + 3]);
  outputs.values[8 * i + 5] = detailSurfaceWeights(hsv);
  vec4 ground = calibratedGround(calibration.rows, inputs.linearRgb[i].rgb);
  outputs.values[8 * i + 6] = ground;
  float l = logColourScore(detail.reference[0].xyz, detail.weights[0].xyz, detail.reference[0].w, vec2(0.0),
                           calibration.exg.xy, ground.xyz, kNoNdvi, ground.w);
  outputs.values[8 * i + 7] = vec4(l, 0.0, 0.0, 0.0);
}
