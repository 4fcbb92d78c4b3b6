#version 450
#extension GL_GOOGLE_include_directive : require
// The compute blade path's vertex stage (render/blade_pass.h): everything, the lighting included,
// was computed once per plant by blades.comp; here one vertex is fetched and projected. The
// outputs are those of the tessellation path's geometry stages (common/plant_geometry.glsl), so
// plant.frag draws both paths alike.
#include "frame_uniforms.glsl"
#include "classify_layout.glsl"
#define BLADE_ACCESS readonly
#include "blade_layout.glsl"

layout(location = 0) out vec3 gColour;  // shadows: r = coverage
layout(location = 1) out vec2 gBlade;
layout(location = 2) flat out uint gFlags;  // bits 0–1: kind; bit 2: shadow; bits 3–7: species

void main() {
  BladeVertex v = bladeVertices[gl_VertexIndex];
  gColour = vec3(unpackHalf2x16(v.colour.x), unpackHalf2x16(v.colour.y).x);
  gBlade = unpackSnorm2x16(v.blade);
  gFlags = ((v.plant >> kBladeKindShift) & 3u) | ((v.plant & kBladeShadowBit) != 0u ? 4u : 0u) | (v.species << 3u);
  gl_Position = frame.viewProj * vec4(v.pos, 1.0);
}
