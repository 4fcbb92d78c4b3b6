#ifndef SIMULATION_FIELDS_GLSL
#define SIMULATION_FIELDS_GLSL
// What drawn plants read of the shared simulation (set 0, bindings 1–3: render/simulation_pass.h):
// the wind grid's moments, bilinear between the virtual blades at the 4 m cells' centres, and the
// interaction field's texel under a point. Both grids are world-aligned and toroidal
// (simulation/shared/simulation_layout.glsl); a point outside a window reads nothing (no moment,
// no trail). Positions are camera-relative.
#include "simulation_block.glsl"
layout(set = 0, binding = 2, std430) readonly buffer WindCells { WindCellGpu windCells[]; };
layout(set = 0, binding = 3, std430) readonly buffer InteractionField { vec4 fieldTexels[]; };

BladeMoments windCellMoments(ivec2 cell) {
  BladeMoments m;
  int at = windCellIndex(cell);
  if (at < 0) {
    for (int i = 0; i < kBladeHinges; ++i) m.m[i] = vec2(0.0);
    return m;
  }
  WindCellGpu c = windCells[at];
  m.m[0] = c.moments01.xy;
  m.m[1] = c.moments01.zw;
  m.m[2] = c.moments23.xy;
  m.m[3] = c.moments23.zw;
  return m;
}

// Bilinear between the four cell centres around p.
BladeMoments momentsAt(vec3 p) {
  vec2 q = (sim.windCamera.xy + p.xy) / kWindCellM - 0.5;
  vec2 f = floor(q);
  vec2 w = q - f;
  ivec2 c = sim.windCells.xy + ivec2(f);
  BladeMoments a = windCellMoments(c), b = windCellMoments(c + ivec2(1, 0));
  BladeMoments d = windCellMoments(c + ivec2(0, 1)), e = windCellMoments(c + ivec2(1, 1));
  BladeMoments r;
  for (int i = 0; i < kBladeHinges; ++i) r.m[i] = mix(mix(a.m[i], b.m[i], w.x), mix(d.m[i], e.m[i], w.x), w.y);
  return r;
}

// The interaction texel (xy: bend direction, z: strength) under p; 0 outside the window.
vec4 interactionAt(vec3 p) {
  int at = fieldTexelIndex(p);
  return at < 0 ? vec4(0.0) : fieldTexels[at];
}
#endif
