// A plant's root and parameters from the Philox slots of vegetation/plant_seeding.cpp (height,
// width and stiffness scaled by s′ as vegetation/species_catalog.h's sPrimeFactor, height and
// width faded; orientation — phototropic where the species says so — and colour modulation):
// shared by the species pipelines and the markers. Needs
// frame_uniforms.glsl, philox.glsl, seeding.glsl, classify_layout.glsl, simulation_fields.glsl and a
// `catalog` block.

// vegetation/species_catalog.h: kSPrimeHeightLo, kSPrimeWidthLo, kSPrimeStiffnessLo.
const float kSPrimeHeightLo = 0.6, kSPrimeWidthLo = 0.8, kSPrimeStiffnessLo = 0.85;
float sPrimeFactor(float lo, float sPrime) { return lo + (1.0 - lo) * sPrime; }

struct PlantParams {
  vec3 root;          // camera-relative
  float height;       // m, faded
  float stiffness;    // k′
  float orientation;  // rad about the vertical
  float width;        // m, faded
  float colourModulation;
  float sPrime;
  // The shared simulation's bend (plant_common.glsl plantMotion; simulation/shared/blade_response.glsl):
  // moving 0 until plantMotion sets it, and for plants that do not move (gravel, markers).
  BladeRest rest;
  BladeBend bend;
  float pressed;  // 0 … 1: how far the interaction field and colliders lay it down (lit as canopy top)
};

PlantParams plantParams(PlantCluster g, SeedTriangle t, uint seed) {
  Species sp = catalog.species[g.species];
  uvec2 key = uvec2(t.keyLo, t.keyHi);
  vec2 r = seedPoint(key, g.cluster, seed);
  PlantParams p;
  p.root = t.v0.xyz + r.x * (t.v1.xyz - t.v0.xyz) + r.y * (t.v2.xyz - t.v0.xyz);
  uvec2 hs = philoxDraw(key, g.cluster, kSlotHeightStiffness + seed);
  uvec2 ow = philoxDraw(key, g.cluster, kSlotOrientationWidth + seed);
  uvec2 cm = philoxDraw(key, g.cluster, kSlotColourSpecies + seed);
  p.height = mix(sp.heightStiffness.x, sp.heightStiffness.y, philoxU01(hs.x)) * sPrimeFactor(kSPrimeHeightLo, g.sPrime) *
             g.fade;
  p.stiffness = mix(sp.heightStiffness.z, sp.heightStiffness.w, philoxU01(hs.y)) * sPrimeFactor(kSPrimeStiffnessLo, g.sPrime);
  // Uniform about the vertical, or (phototropism) spread less and less about the sun's azimuth:
  // 0 keeps the uniform angle, 1 leans every blade towards the sun. Seed 001 §2.3 centres the
  // distribution "opposite to the direction of sunlight", i.e. against the light's travel, which
  // is towards the sun, as plants grow (positive phototropism); frame.sunDirection points to the
  // sun. (The uniform angle is vegetation::Plant::orientationRad; the sun's pull is the renderer's.)
  p.orientation = 6.28318530718 * philoxU01(ow.x);
  if (sp.marker.w > 0.0) {
    float towardsSun = atan(frame.sunDirection.y, frame.sunDirection.x);
    p.orientation = towardsSun + (p.orientation - 3.14159265359) * (1.0 - sp.marker.w);
  }
  p.width = mix(sp.widthColour.x, sp.widthColour.y, philoxU01(ow.y)) * sPrimeFactor(kSPrimeWidthLo, g.sPrime) * g.fade;
  p.colourModulation = mix(sp.widthColour.z, sp.widthColour.w, philoxU01(cm.x));
  p.sPrime = g.sPrime;
  p.bend.moving = 0.0;
  p.pressed = 0.0;
  return p;
}

