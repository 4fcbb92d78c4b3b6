// The colour of a plant vertex: core seed 001_3eca9f2c7752e4fb.txt §2.4, eq. 14's ambient +
// Lambert + Phong specular plus eq. 13's translucency I_t = I_i k_t max(−n·ω, 0) exp(α / (n·ω))
// for light from behind the blade; coefficients from the imagery colour under the plant (the same
// albedo the terrain pass gives that ground, so plants fade into the textured far terrain),
// darkened towards the ground by the neighbours' occlusion (Reeves and Blau 1985; seed 004
// §2.3's height-dependent light), then the aerial perspective of the terrain.
//
// Evaluated per vertex (issue 17): the geometry stages of the tessellation path and blades.comp of
// the compute path call it, plant.frag only interpolates. A blade is a few pixels wide and its
// 1–5 segments follow its curvature, so per-vertex lighting loses nothing visible, while per
// fragment it was most of the plants pass on GPUs whose fragment units are few (the H200 runs
// them on 2 of 66 TPCs). Needs frame_uniforms.glsl and atmosphere.glsl.

const float kPlantAttenuation = 0.6;      // α of eq. 13: light absorbed crossing a blade of unit width

const uint kPlantKindBlade = 0u, kPlantKindStone = 1u, kPlantKindHead = 2u;

// pos: camera-relative; normal: the surface's (either side); blade.y: 0 root … 1 tip;
// ground: the albedo under the root (linear, the terrain's own: issue 39 item 5, plants average to
// the ground they grow from); modulation: the plant's colour factor (around 1); up: the ground's
// unit normal under the plant. Lit by the frame's sun and sky (atmosphere.glsl) as the terrain is.
vec3 plantColour(vec3 pos, vec3 normal, vec2 blade, vec3 ground, float modulation, uint kind, vec3 up) {
  vec3 n = normalize(normal);
  vec3 v = normalize(-pos);
  if (dot(n, v) < 0.0) n = -n;  // blades are two-sided: shade the face we see
  // A canopy of thin blades, or a bed of stones, is lit much like the ground it covers (a slope
  // turned from the sun stays dark): bend the normal towards the ground's.
  vec3 nLight = normalize(mix(n, up, 0.7));
  vec3 l = frame.sunDirection.xyz;
  float ndl = dot(nLight, l);
  vec3 albedo = ground * modulation;
  // Flower heads: yellow, at a brightness relative to the ground's (1.8 × its luminance), not a
  // fixed albedo: a fixed 0.5 stood six times brighter than a meadow of 8 % albedo, a bright
  // carpet from 10 m out that does not average to the imagery (issue 39 item 5).
  if (kind == kPlantKindHead) {
    float luma = dot(albedo, vec3(0.2126, 0.7152, 0.0722));
    albedo = mix(albedo, vec3(1.0, 0.82, 0.22) * (1.8 / 0.8145) * luma, 0.6);
  }
  // Occlusion by the neighbours: dark at the root, the sunlit top of the canopy a little brighter
  // than the bare ground (stones and heads: none); the canopy seen from afar averages near 1.
  float occlusion = kind != kPlantKindBlade ? 1.0 : mix(0.55, 1.15, blade.y);
  vec3 kd = albedo * occlusion / kAtmospherePi;
  vec3 kt = kd * vec3(0.9, 1.0, 0.55);  // light through a leaf turns yellow-green
  float ks = (kind == kPlantKindBlade ? 0.015 : 0.01) * occlusion;
  vec3 ii = sunIlluminance() * sunShadow(pos, up);  // the trees' shadows (the blades' own planar ones are drawn apart)
  vec3 r = reflect(-l, nLight);
  vec3 lit = kd * skyIrradiance(nLight) + ii * (kd * max(ndl, 0.0) + ks / kAtmospherePi * pow(max(dot(v, r), 0.0), 32.0));
  float ndlFace = dot(n, l);  // translucency goes through the blade's own face
  if (ndlFace < 0.0 && kind == kPlantKindBlade) lit += ii * kt * (-ndlFace) * exp(kPlantAttenuation / ndlFace);  // eq. 13
  return applyAerialPerspective(lit, pos);
}
