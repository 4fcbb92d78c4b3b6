// Species from the base colour, core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3
// eq. 16–18: the GLSL twin of vegetation/species_choice.cpp (operation for operation). Needs
// colour_score.glsl and a `catalog` uniform block (classify_layout.glsl's Species array).
//
// `ground`: HSV (xyz) and ExG (w) of the calibrated colour (colour_calibration.glsl's
// calibratedGround); `ndvi`: kNoNdvi where there is none. Returns (species index, s′), species −1
// when the seed is rejected (bare soil, or no species scores above its threshold).
// `allowed`: bit i set where the landcover class under the plant allows species i
// (vegetation/landcover_species.h; 0xffffffffu without landcover), tested before the score.
vec2 chooseSpeciesAllowed(vec4 ground, float ndvi, float z, uint allowed) {
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
  if (best < 0) return vec2(-1.0, 0.0);
  float ratio = second < 0 ? 0.0 : 1.0 / (1.0 + exp(l0 - l1));
  int pick = best;
  float sPrime = 1.0 - ratio;
  if (z < ratio) {
    pick = second;
    sPrime = ratio;
  }
  if (catalog.species[pick].flags.x != 0u) return vec2(-1.0, 0.0);
  return vec2(float(pick), sPrime);
}

vec2 chooseSpecies(vec4 ground, float ndvi, float z) { return chooseSpeciesAllowed(ground, ndvi, z, 0xffffffffu); }
