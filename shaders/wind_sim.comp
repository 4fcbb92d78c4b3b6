#version 450
#extension GL_GOOGLE_include_directive : require
// The wind grid's step (issue 19; render/simulation_pass.h): one thread per virtual blade of the
// 128 × 128 toroidal grid. A blade whose cell entered the window this frame (or the simulation
// restarted) starts at rest under the wind of the first sub-step; then the frame's fixed sub-steps
// of the virtually-inertial model (simulation/shared/virtual_blade.glsl, seed 004 §3.1–3.3), each
// under the wind at its time (simulation/shared/wind_field.glsl). Writes the state back and the
// cell's wind and moments for the plants (shaders/common/simulation_fields.glsl).
layout(local_size_x = 8, local_size_y = 8) in;
#include "simulation_block.glsl"
layout(set = 1, binding = 0, std430) buffer VirtualBlades { VirtualBladeGpu blades[]; };
layout(set = 1, binding = 1, std430) writeonly buffer WindCellsOut { WindCellGpu cells[]; };

void main() {
  ivec2 index = ivec2(gl_GlobalInvocationID.xy);
  ivec2 first = sim.windCells.zw;
  ivec2 cell = first + ((index - first) & (kWindGrid - 1));  // the world cell held at `index`
  uint at = uint(index.x + index.y * kWindGrid);
  vec2 centre = (vec2(cell) + 0.5) * kWindCellM;
  float t0 = sim.clock.y, h = sim.clock.z;
  int steps = int(sim.clock.x + 0.5);

  VirtualBladeGpu g = blades[at];
  VirtualBlade b;
  if (g.cell.xy != cell || g.cell.z != sim.counts.w) {
    b = virtualBladeAtRest(windAt(centre, t0));
  } else {
    for (int i = 0; i < kBladeHinges; ++i) {
      b.lean[i] = g.hinge[i].xy;
      b.rate[i] = g.hinge[i].zw;
    }
  }
  for (int k = 0; k < steps; ++k) virtualBladeStep(b, windAt(centre, t0 + float(k) * h), h);
  for (int i = 0; i < kBladeHinges; ++i) g.hinge[i] = vec4(b.lean[i], b.rate[i]);
  g.cell = ivec4(cell, sim.counts.w, 0);
  blades[at] = g;

  BladeMoments m = virtualBladeMoments(b);
  WindCellGpu c;
  c.wind = vec4(windAt(centre, sim.clock.w), 0.0);
  c.moments01 = vec4(m.m[0], m.m[1]);
  c.moments23 = vec4(m.m[2], m.m[3]);
  cells[at] = c;
}
