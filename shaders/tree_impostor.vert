#version 460
#extension GL_GOOGLE_include_directive : require
// Octahedral impostors of trees (issue 20, common/tree_impostor.glsl): a triangle per entry of
// the classify pass's impostor list, drawn in the basis of the captured view nearest the
// direction the tree is seen from, scaled and turned like the tree's model (tree.vert), its top
// swaying with the trunk's amplitude in the shared wind (the impostor moves as a whole): the
// triangle of common/tree_impostor_frame.glsl, which the shadow cascades' compute rasteriser
// (tree_shadow_raster.comp) builds turned to the sun.
#include "common/frame_uniforms.glsl"
#include "common/simulation_block.glsl"
#include "simulation/shared/tree_bending.glsl"
#include "common/tree_layout.glsl"
#include "common/tree_push.glsl"
#include "common/tree_impostor.glsl"
#include "common/tree_impostor_frame.glsl"
#include "common/atmosphere.glsl"
#include "common/tree_shading.glsl"
#include "common/hiz_occlusion.glsl"

layout(location = 0) out vec3 vPos;
layout(location = 1) out vec2 vUv;  // in the atlas (0 … 1)
layout(location = 2) flat out uint vLayer;
layout(location = 3) flat out float vThreshold;
layout(location = 4) flat out uint vInstance;
// The tree's turn (treeRotation), its columns: the captured model-space normal into the world
// without the six sines and cosines per fragment.
layout(location = 5) flat out vec3 vRotX;
layout(location = 6) flat out vec3 vRotY;
layout(location = 7) flat out vec3 vTowards;  // the captured view's axis, world
// The captured colour's factor for this tree (treeImpostorFactor × its colour factor), per tree.
layout(location = 8) flat out vec3 vTint;
layout(location = 9) flat out vec3 vRotZ;
layout(location = 10) flat out vec4 vSky;   // the aerial perspective at the tree's centre
layout(location = 11) flat out float vSun;  // the sun shadow there
layout(location = 12) flat out vec4 vRect;  // the rectangle the model fills, in the atlas: centre, half extents

void main() {
  uvec4 entry = treeVisible[gl_InstanceIndex];
  TreeInstanceGpu t = treeInstances[entry.x];
  TreeModelGpu m = trees.models[push.model];
  TreeImpostorFrame f = treeImpostorFrame(entry, t, m, false);
  vec3 rel = treeImpostorCorner(f, t, m, uint(gl_VertexIndex % 3), vUv);
  vPos = rel;
  vRect = treeImpostorRect(f, m);
  vLayer = m.mesh1.w;
  vThreshold = uintBitsToFloat(entry.y);
  vInstance = entry.x;
  vRotX = f.rotation[0];
  vRotY = f.rotation[1];
  vRotZ = f.rotation[2];
  vTowards = f.rotation * f.dc;
  vec4 ground = treeInstanceColour(t.colour);
  vTint = treeImpostorFactor(m.leaf.rgb, ground.rgb) * ground.a;
  vSky = treeVertexAtmosphere(f.centreRel);
  // The shadow of other trees: looked up just outside this one's crown, towards the sun (its own
  // centre is always in its own shadow).
  vec3 sunward = f.centreRel + frame.sunDirection.xyz * (0.6 * max(t.heightM, t.crownM));
  vSun = sunShadow(sunward, vec3(0.0, 0.0, 1.0));
  gl_Position = frame.viewProj * vec4(rel, 1.0);
  // An impostor behind the terrain is dropped here, before any of its fragments: the quad's
  // sphere (its half extents, scaled, plus the sway) against this frame's Hi-Z pyramid. Every
  // vertex of the quad decides alike, so the quad goes whole.
  float reach = length(f.extent) * max(f.scale.x, f.scale.y) + 0.1 * t.heightM;
  if (hiddenByTerrain(f.centreRel, reach)) gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
}
