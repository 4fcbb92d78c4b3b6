#ifndef TREE_SHADING_GLSL
#define TREE_SHADING_GLSL
// How tree fragments look (issue 20), shared by the models (tree.frag) and the impostors
// (tree_impostor.frag): alpha to coverage computed into the
// sample mask (as plant.frag: the fixed-function path resolves to wrong colours on lavapipe), and
// the lighting — ambient + Lambert for bark and the lit side of leaves, and for leaves lit from
// behind the sun through the leaf (seed 002 §3.3: L_t, here with a constant average translucency
// ρ_t per species instead of the measured maps and the multi-dipole). Needs frame_uniforms.glsl
// and atmosphere.glsl.

// k of the n samples for coverage `alpha`, rotated and dithered per pixel (plant.frag's scheme);
// 0 when nothing covers.
uint treeSampleMask(float alpha, uint samples, float dither) {
  samples = max(samples, 1u);
  uint k = min(uint(alpha * float(samples) + dither), samples);
  if (k == 0u) return 0u;
  uint first = uint(dither * 16.0) % samples;
  uint bits = k >= 32u ? 0xffffffffu : (1u << k) - 1u;
  return ((bits << first) | (bits >> (samples - first))) & (samples >= 32u ? 0xffffffffu : (1u << samples) - 1u);
}

// The lighting at a fragment, without the aerial perspective: n the face's unit normal towards
// the viewer; leaf: a card (else bark); occlusion: 0 deep in the crown … 1 at its surface; sun:
// the sun shadow's factor (sunShadow). What varies slowly over a tree — the shadow lookup and the
// aerial perspective — the vertex stages evaluate (treeVertexLight): the H200 shades fragments on
// 2 of its 66 TPCs, and the trees' cards overlap many times.
// The leaves' albedo (issue 39 item 5): as bright as the imagery under the tree × kCanopyGain —
// from afar a crown's lit and shaded leaves and the shadow around it average to the photographed
// canopy — with a hue half the species' own leaf and half the imagery's, so a conifer at a
// meadow's edge stays a conifer up close; the species' own colour where there is no imagery
// (rgb 0).
const float kCanopyGain = 1.6;
float treeLuminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
vec3 treeLeafAlbedo(vec3 speciesLeaf, vec3 ground) {
  if (dot(ground, vec3(1.0)) <= 0.0) return speciesLeaf;
  vec3 target = min(ground * kCanopyGain, vec3(0.9));
  vec3 leafAtTarget = speciesLeaf * treeLuminance(target) / max(treeLuminance(speciesLeaf), 1e-4);
  return mix(leafAtTarget, target, 0.5);
}
// What an impostor's captured colour (the species' leaves, its bark) is multiplied by for this
// tree: the leaves' change, its chroma halved again so the captured bark keeps its brown.
vec3 treeImpostorFactor(vec3 speciesLeaf, vec3 ground) {
  vec3 ratio = treeLeafAlbedo(speciesLeaf, ground) / max(speciesLeaf, vec3(1e-3));
  float grey = treeLuminance(treeLeafAlbedo(speciesLeaf, ground)) / max(treeLuminance(speciesLeaf), 1e-4);
  return mix(vec3(grey), ratio, 0.5);
}

// An instance's colour word (render/tree_layout.h): the imagery under it decoded to linear, and
// its colour factor.
vec4 treeInstanceColour(uint packed) {
  vec4 c = unpackUnorm4x8(packed);
  vec3 linear = mix(c.rgb / 12.92, pow((c.rgb + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c.rgb));
  return vec4(linear, c.a);
}

// The crowns' cores (tree_core.frag, and the impostor capture): foliage in its own shade.
const float kTreeCoreShade = 0.6;

// Lambertian under the frame's sun and sky (atmosphere.glsl): the sky light reaches into the crown
// as the occlusion allows, the sun as its shadow map does.
vec3 treeLight(vec3 n, vec3 albedo, float translucency, bool leaf, float occlusion, float sun) {
  vec3 l = frame.sunDirection.xyz;
  float ndl = dot(n, l);
  vec3 ii = sunIlluminance() * sun;
  vec3 kd = albedo / kAtmospherePi;
  vec3 lit = kd * (skyIrradiance(n) * mix(0.35, 1.0, occlusion) + ii * max(ndl, 0.0));
  if (leaf && ndl < 0.0) lit += ii * kd * vec3(0.9, 1.0, 0.5) * translucency * (-ndl);  // through the leaf
  return lit;
}

// Per vertex: the aerial perspective at the point (xyz the air's in-scattered light, w the
// transmittance: colour · w + xyz).
vec4 treeVertexAtmosphere(vec3 pos) { return aerialPerspective(pos); }
#endif
