// The terrain-type table and detail settings (mirrors render/terrain_detail.h, std140), and the
// blend weights of the types for a base colour: s_i / Σ s with s_i the colour score of eq. 16
// (core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3). Needs colour_score.glsl.
// The block is binding 1 of set TERRAIN_DETAIL_SET (2 in the terrain pass; a shader that has no
// other sets may define it as 0 before including this file).
#ifndef TERRAIN_DETAIL_SET
#define TERRAIN_DETAIL_SET 2
#endif

const int kMaxTerrainTypes = 16;  // one per species (vegetation/terrain_types.h)
const int kDetailSurfaces = 4;  // vegetation::DetailSurface: grass, rock, gravel, sand

layout(set = TERRAIN_DETAIL_SET, binding = 1, std140) uniform TerrainDetail {
  vec4 params;   // x: type count, y: fade start (m), z: fade end (m), w: strength
  vec4 tiling;   // x: period (m), y: fine repeats per period, z: coarse repeats per period, w: coarse share
  vec4 reference[kMaxTerrainTypes];  // xyz: reference HSV, w: exponent p
  vec4 weights[kMaxTerrainTypes];    // xyz: channel weights, w: detail surface (texture layer)
  vec4 ndvi[kMaxTerrainTypes];       // x: NDVI reference, y: NDVI weight (colour_score.h)
} detail;

// Blend weights of the table's types for base colour `hsv` and the NDVI there (kNoNdvi: none),
// entries past the count 0: vegetation::terrainTypeWeights, the same scores as the species.
void terrainTypeWeights(vec3 hsv, float ndvi, out float w[kMaxTerrainTypes]) {
  int n = int(detail.params.x);
  float top = -3.4e38;
  for (int i = 0; i < kMaxTerrainTypes; ++i) {
    // Scores raised to kTerrainBlendSharpness (vegetation/terrain_types.h): d^(−p k).
    w[i] = i < n ? logColourScore(detail.reference[i].xyz, detail.weights[i].xyz, detail.reference[i].w * 3.0,
                                  detail.ndvi[i].xy, hsv, ndvi)
                 : 0.0;
    if (i < n) top = max(top, w[i]);
  }
  float sum = 0.0;
  for (int i = 0; i < kMaxTerrainTypes; ++i) {
    w[i] = i < n ? exp(w[i] - top) : 0.0;  // the best type gets exp(0) = 1
    sum += w[i];
  }
  for (int i = 0; i < kMaxTerrainTypes; ++i) w[i] = sum > 0.0 ? w[i] / sum : 0.0;  // no types: all 0
}

void terrainTypeWeights(vec3 hsv, out float w[kMaxTerrainTypes]) { terrainTypeWeights(hsv, kNoNdvi, w); }

// The weights summed per detail surface (x grass, y rock, z gravel, w sand).
vec4 detailSurfaceWeights(vec3 hsv, float ndvi) {
  float w[kMaxTerrainTypes];
  terrainTypeWeights(hsv, ndvi, w);
  vec4 surfaces = vec4(0.0);
  for (int i = 0; i < kMaxTerrainTypes; ++i) surfaces[int(detail.weights[i].w)] += w[i];
  return surfaces;
}

vec4 detailSurfaceWeights(vec3 hsv) { return detailSurfaceWeights(hsv, kNoNdvi); }
