#version 450
// Automatic exposure, step 2 (common/exposure.glsl): the EV100 of this frame from the histogram
// (or the fixed one), smoothed over time when the window asks, written to the state (the tone
// map reads it) and to the frame slot's read-back word. One invocation: 64 bins.
#extension GL_GOOGLE_include_directive : require
#include "common/exposure.glsl"
layout(local_size_x = 1) in;
layout(set = 0, binding = 1, std430) buffer State { ExposureState state; };
layout(set = 0, binding = 3, std430) writeonly buffer Readback { float slotEv[]; };
layout(push_constant) uniform Push {
  vec4 params;   // x: mode (kTone*), y: fixed EV100, z: 1 = adapt over time, w: seconds since the last frame
  uvec4 target;  // x: frame slot, y, z: width, height
} pc;

float histogramEv() {
  uint total = 0u;
  for (int b = 0; b < kExposureBins; ++b) total += state.bins[b];
  if (total == 0u) return evForLogLuminance(-3.0);
  float lo = kExposureLow * float(total), hi = kExposureHigh * float(total);
  float below = 0.0, weight = 0.0, sum = 0.0;
  for (int b = 0; b < kExposureBins; ++b) {
    float n = float(state.bins[b]);
    float take = max(min(below + n, hi) - max(below, lo), 0.0);  // this bin's pixels inside [lo, hi]
    float centre = kLogLumMin + (float(b) + 0.5) * (kLogLumMax - kLogLumMin) / float(kExposureBins);
    sum += take * centre;
    weight += take;
    below += n;
  }
  return evForLogLuminance(weight > 0.0 ? sum / weight : -3.0);
}

void main() {
  uint mode = uint(pc.params.x);
  float ev = mode == kToneFixed ? pc.params.y : (mode == kToneIdentity ? log2(kLuminanceUnitCdM2 / 1.2) : histogramEv());
  if (mode == kToneAuto && pc.params.z > 0.5 && state.valid == 1u)
    ev = state.ev + (ev - state.ev) * (1.0 - exp(-kAdaptPerS * pc.params.w));
  state.ev = ev;
  state.valid = 1u;
  slotEv[pc.target.x] = ev;
}
