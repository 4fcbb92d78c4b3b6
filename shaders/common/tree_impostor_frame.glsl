#ifndef TREE_IMPOSTOR_FRAME_GLSL
#define TREE_IMPOSTOR_FRAME_GLSL
// One octahedral impostor's triangle (issue 20): the captured view nearest the direction the tree
// is seen from, the rectangle the model fills in it and the one triangle that holds that
// rectangle, scaled and turned like the tree's model, its top swaying with the trunk's amplitude in
// the shared wind. The colour pass's vertex stage (tree_impostor.vert) and the shadow cascades'
// compute rasteriser (tree_shadow_raster.comp) build the same triangle from the same entry.
// Needs frame_uniforms.glsl, simulation_block.glsl, simulation/shared/tree_bending.glsl,
// tree_layout.glsl, tree_push.glsl (treeTime) and tree_impostor.glsl.

struct TreeImpostorFrame {
  vec3 root;       // the tree's root, camera-relative
  vec3 centreRel;  // the crown's centre, camera-relative
  vec2 scale;      // treeScale: x horizontal, y vertical
  vec2 cell;       // the captured view's cell in the atlas
  vec3 dc;         // that view's direction (model frame)
  vec2 half_;      // the rectangle the model fills in the cell (model metres)
  vec3 right, up;  // the triangle's basis (model frame)
  vec2 extent;     // its rectangle's half extents (model metres)
  float apex, base;
  vec3 wind;       // the wind at the tree, model frame
  mat3 rotation;   // treeRotation
};

// `towardsSun`: the triangle stands across the sun (the shadow cascades), not across the captured
// view nearest the camera.
TreeImpostorFrame treeImpostorFrame(uvec4 entry, TreeInstanceGpu t, TreeModelGpu m, bool towardsSun) {
  TreeImpostorFrame f;
  uint seed = t.seed;
  f.scale = treeScale(t, m);
  f.root = t.position - trees.camera.xyz;
  f.centreRel = f.root + vec3(0.0, 0.0, m.shape.w * f.scale.y);
  // The direction the tree is seen from, in the model's frame; the nearest captured cell.
  // (The shadow: seen from the sun, so the cascade holds the silhouette the sun sees.)
  vec3 d = treeUnrotateYaw(towardsSun ? frame.sunDirection.xyz : normalize(-f.centreRel), seed);
  uint g = trees.counts.w;
  f.cell = clamp(floor(treeImpostorUv(d) * float(g)), vec2(0.0), vec2(float(g) - 1.0));
  f.dc = treeImpostorDirection((f.cell + 0.5) / float(g));
  float r = m.shape.z;
  // The quad holds what the model covers seen along dc — a cylinder of the crown's radius and the
  // model's height about its centre — not the captured square: a side view of a tree is a third
  // as wide as it is tall (the H200 spent 26 ms a frame on the square's empty corners).
  float sinE = clamp(f.dc.z, 0.0, 1.0), cosE = sqrt(1.0 - sinE * sinE);
  float rc = 1.08 * m.shape.y, hh = 0.55 * m.shape.x;
  f.half_ = min(vec2(rc, hh * cosE + rc * sinE), vec2(r));
  // Towards the sun the quad stands across the sun itself, not across the captured view nearest
  // it (cells are 10–20° apart): the captured silhouette stretched over the cylinder as the sun
  // sees it. Otherwise a shadow is as long as the nearest view's, not the sun's (a 15 m conifer
  // under a 35° sun cast 17 m instead of 21: tests/render/tree_shadow_test.cpp).
  vec3 seen = towardsSun ? d : f.dc;
  treeImpostorBasis(seen, f.right, f.up);
  float sinS = clamp(seen.z, 0.0, 1.0), cosS = sqrt(1.0 - sinS * sinS);
  f.extent = min(vec2(rc, hh * cosS + rc * sinS), vec2(r));
  // One triangle that holds the model (render/tree_impostor_outline.h): apex (0, a), base (±b, 0)
  // in the rectangle's units (up: 0 at its bottom … 1 at its top); what lies outside the
  // rectangle is dropped per pixel.
  int bin = min(int(sinE * 4.0), 3);
  f.apex = m.triangleApex[bin];
  f.base = m.triangleBase[bin];
  f.wind = treeUnrotateYaw(vec3(uintBitsToFloat(entry.z), uintBitsToFloat(entry.w), 0.0), seed);
  f.rotation = treeRotation(seed);
  return f;
}

// The rectangle the model fills, in the atlas: centre, half extents.
vec4 treeImpostorRect(TreeImpostorFrame f, TreeModelGpu m) {
  float g = float(trees.counts.w);
  return vec4((f.cell + 0.5) / g, 0.5 * f.half_ / (m.shape.z * g));
}

// Corner `k` of the triangle (0, 1: the base's ends, 2: the apex): camera-relative, swaying with
// the trunk's bend at its height; `uv` its place in the atlas (0 … 1).
vec3 treeImpostorCorner(TreeImpostorFrame f, TreeInstanceGpu t, TreeModelGpu m, uint k, out vec2 uv) {
  vec2 c = k == 2u ? vec2(0.0, 2.0 * f.apex - 1.0) : vec2(k == 0u ? -f.base : f.base, -1.0);
  vec3 modelPoint = vec3(0.0, 0.0, m.shape.w) + f.right * (c.x * f.extent.x) + f.up * (c.y * f.extent.y);
  if (dot(f.wind, f.wind) > 1e-6) {
    TreeBranchGpu trunk = treeBranches[m.mesh0.w];
    vec2 amp = branchAmplitude(f.wind, trunk.rC4.xyz, trunk.sFrequency.xyz, trunk.link.w, trunk.sFrequency.w,
                               float(t.seed & 1023u) * 0.00614, treeTime());
    float x = clamp(modelPoint.z / trunk.originLength.w, 0.0, 1.0);
    modelPoint += branchOffset(trunk.tC2.xyz, trunk.rC4.xyz, trunk.sFrequency.xyz, trunk.originLength.w, trunk.tC2.w,
                               trunk.rC4.w, x, amp);
  }
  float g = float(trees.counts.w);
  uv = (f.cell + 0.5 + 0.5 * vec2(c.x * f.half_.x, -c.y * f.half_.y) / m.shape.z) / g;
  return f.root + f.rotation * vec3(modelPoint.xy * f.scale.x, modelPoint.z * f.scale.y);
}

#endif
