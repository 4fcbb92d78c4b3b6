// Species from the base colour, core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3
// eq. 16–18: the GLSL twin of vegetation/species_choice.cpp (operation for operation). Needs
// colour_score.glsl and a `catalog` uniform block (classify_layout.glsl's Species array).
//
// `ground`: HSV (xyz) and ExG (w) of the calibrated colour (colour_calibration.glsl's
// calibratedGround); `ndvi`: kNoNdvi where there is none. Returns (species index, s′), species −1
// when the seed is rejected (bare soil, or no species scores above its threshold).
// `allowed`: bit i set where the landcover class under the plant allows species i
// (vegetation/landcover_species.h; 0xffffffffu without landcover), tested before the score.

// The two best (vegetation::speciesCandidates): x first, y second (−1: none), z ratio s1 / (s0 + s1).
vec3 speciesCandidates(vec4 ground, float ndvi, uint allowed) {
  int best = -1, second = -1;
  float l0 = 0.0, l1 = 0.0;
  for (uint i = 0u; i < catalog.speciesCount.x; ++i) {
    if (((allowed >> i) & 1u) == 0u) continue;  // the landcover class does not allow it
    Species sp = catalog.species[i];
    float l = logColourScore(sp.reference.xyz, sp.weights.xyz, sp.reference.w, sp.ground.zw, sp.index.xy, ground.xyz,
                             ndvi, ground.w);
    if (l < sp.weights.w) continue;  // under its threshold: score 0
    if (best < 0 || l > l0) {
      second = best;
      l1 = l0;
      best = int(i);
      l0 = l;
    } else if (second < 0 || l > l1) {
      second = int(i);
      l1 = l;
    }
  }
  float ratio = second < 0 ? 0.0 : 1.0 / (1.0 + exp(l0 - l1));
  return vec3(float(best), float(second), ratio);
}

vec2 chooseSpeciesAllowed(vec4 ground, float ndvi, float z, uint allowed) {
  vec3 c = speciesCandidates(ground, ndvi, allowed);
  if (c.x < 0.0) return vec2(-1.0, 0.0);
  float ratio = c.z;
  int pick = int(c.x);
  float sPrime = 1.0 - ratio;
  if (z < ratio) {
    pick = int(c.y);
    sPrime = ratio;
  }
  if (catalog.species[pick].flags.x != 0u) return vec2(-1.0, 0.0);
  return vec2(float(pick), sPrime);
}

// vegetation::treeStandShare.
const float kStandShareLo = 0.25, kStandShareHi = 0.75;
float treeStandShare(float sPrime) {
  float t = clamp((sPrime - kStandShareLo) / (kStandShareHi - kStandShareLo), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// vegetation::choosePlantSpecies: a tree's pick is forest floor where the tree would stand, else
// the other of the two best.
vec2 choosePlantSpecies(vec4 ground, float ndvi, float z, uint allowed) {
  vec3 c = speciesCandidates(ground, ndvi, allowed);
  if (c.x < 0.0) return vec2(-1.0, 0.0);
  float ratio = c.z;
  bool second = z < ratio;
  int pick = second ? int(c.y) : int(c.x);
  int other = second ? int(c.x) : int(c.y);
  float sPrime = second ? ratio : 1.0 - ratio;
  float u = second ? z / ratio : (z - ratio) / (1.0 - ratio);
  if (catalog.species[pick].flags.w != 0u) {  // a tree
    if (other < 0 || u < treeStandShare(sPrime)) return vec2(-1.0, 0.0);
    pick = other;
    sPrime = 1.0 - sPrime;
  }
  if (catalog.species[pick].flags.x != 0u) return vec2(-1.0, 0.0);  // bare, or a tree too
  return vec2(float(pick), sPrime);
}

vec2 chooseSpecies(vec4 ground, float ndvi, float z) { return chooseSpeciesAllowed(ground, ndvi, z, 0xffffffffu); }
