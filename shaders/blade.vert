#version 450
#extension GL_GOOGLE_include_directive : require
// The compute blade path's vertex stage (render/blade_pass.h): everything was computed once per
// plant by blades.comp; here one vertex and its plant record are fetched and projected. The
// outputs are those of the tessellation path's geometry stages (common/plant_geometry.glsl), so
// plant.frag shades both paths alike.
#include "frame_uniforms.glsl"
#include "classify_layout.glsl"
#define BLADE_ACCESS readonly
#include "blade_layout.glsl"

layout(location = 0) out vec3 gPos;
layout(location = 1) out vec3 gNormal;
layout(location = 2) out vec2 gBlade;
layout(location = 3) flat out vec3 gGround;
layout(location = 4) flat out vec4 gPlant;  // colour modulation, s′, kind, shadow (1)
layout(location = 5) flat out vec3 gUp;

void main() {
  BladeVertex v = bladeVertices[gl_VertexIndex];
  BladePlant p = bladePlants[v.plant & kBladePlantMask];
  gPos = v.pos;
  gNormal = v.normal;
  gBlade = unpackSnorm2x16(v.blade);
  gGround = p.groundMod.rgb;
  gPlant = vec4(p.groundMod.a, p.upSPrime.w, float((v.plant >> kBladeKindShift) & 3u),
                (v.plant & kBladeShadowBit) != 0u ? 1.0 : 0.0);
  gUp = p.upSPrime.xyz;
  gl_Position = frame.viewProj * vec4(v.pos, 1.0);
}
