#version 450
#extension GL_GOOGLE_include_directive : require
// Forward terrain shading: each fragment shaded where it is rasterised (the path for devices
// whose colour target cannot be a multisampled storage image; render/terrain_pass.h).
#include "frame_uniforms.glsl"
#include "atmosphere.glsl"
#include "colour_score.glsl"
#include "terrain_detail.glsl"
#include "terrain_palette.glsl"
#include "terrain_draw.glsl"
#include "terrain_shading.glsl"
#include "aov.glsl"
layout(location = 0) in vec3 inOffset;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in float inHeightMsl;
layout(location = 3) in vec2 inUv;
layout(location = 4) flat in uint inPiece;
layout(location = 0) out vec4 outColor;

void main() {
  TerrainPoint p = TerrainPoint(inOffset, inNormal, inHeightMsl, inUv, dFdx(inOffset), dFdy(inOffset));
  Piece pc = drawPieces[inPiece];
  outColor = aovGround(vec4(shadeTerrain(p, TerrainImagery(pc.imageryUv, pc.previousUv, pc.layers)), 1.0));
}
