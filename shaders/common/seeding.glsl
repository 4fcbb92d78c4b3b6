// Plant seeding on a seed triangle, core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2,
// §3.4 (eq. 19–25): the GLSL twin of vegetation/stratified_clusters.* and plant_seeding.*,
// integer for integer (tests/render/classify_gpu_test.cpp compares them). Include philox.glsl
// and colour_score.glsl first.

const uint kMaxStratificationLevel = 1000u;
const uint kSlotCentre = 0u;
const uint kSlotSpecies = 1u;
const uint kSlotPosition = 2u;
const uint kSlotHeightStiffness = 64u;
const uint kSlotOrientationWidth = 96u;
const uint kSlotColourSpecies = 128u;
const uint kSlotCanopy = 160u;
const uint kSlotLevelOffset = 255u;

uint pyramidalNumber(uint n) { return n * (n + 1u) * (2u * n + 1u) / 6u; }

// The smallest n with P_n ≥ i: eq. 22's estimate corrected by integer steps.
uint clusterLevel(uint i) {
  float r = pow(3.0 * float(i), 1.0 / 3.0) - 0.5;
  uint n = uint(max(1.0, ceil(r)));
  n = min(n, kMaxStratificationLevel);
  while (pyramidalNumber(n) < i) ++n;
  while (n > 1u && pyramidalNumber(n - 1u) >= i) --n;
  return n;
}

uint gcdU(uint a, uint b) {
  while (b != 0u) {
    uint t = a % b;
    a = b;
    b = t;
  }
  return a;
}

uint strataStride(uint n) {
  if (n == 1u) return 1u;
  uint cells = n * n;
  uint a = (cells * 618u + 500u) / 1000u;
  while (gcdU(a, n) != 1u) ++a;
  return a % cells;
}

uvec2 philoxDraw(uvec2 key, uint cluster, uint slot) { return philox2x32_3(uvec2((cluster << 8) | slot, key.y), key.x); }

// (level, x, y) of cluster c's stratum; cluster 0 covers the whole triangle.
uvec3 clusterStratumOf(uvec2 key, uint c) {
  if (c == 0u) return uvec3(1u, 0u, 0u);
  uint n = clusterLevel(c + 1u);
  uint cells = n * n;
  uint offset = philoxDraw(key, n, kSlotLevelOffset).x;
  uint k = c - pyramidalNumber(n - 1u);
  // (a·k + b) mod n² without 64-bit integers: a, k < n² ≤ 10⁶, so split k.
  uint a = strataStride(n), b = offset % cells;
  uint kHi = k >> 10, kLo = k & 1023u;
  uint s = ((a * kHi) % cells * 1024u % cells + a * kLo % cells + b) % cells;
  return uvec3(n, s % n, s / n);
}

vec2 reflectIntoTriangle(vec2 r) { return r.x + r.y >= 1.0 ? vec2(1.0 - r.y, 1.0 - r.x) : r; }

// The point of stratum (level, x, y) for the unit-square sample f, on the unit triangle: upright
// cell (x, y) when x + y < level, else the inverted cell (level − 1 − y, level − 1 − x).
vec2 pointInStratum(uvec3 s, vec2 f) {
  float n = float(s.x);
  vec2 t = reflectIntoTriangle(f);
  if (s.y + s.z < s.x) return vec2((float(s.y) + t.x) / n, (float(s.z) + t.y) / n);
  return vec2((float(s.x - s.z) - t.x) / n, (float(s.x - s.y) - t.y) / n);
}

// vegetation::groupPriority: the overflow thinning's view-independent priority of a group.
float groupPriority(uvec2 key, uint c, uint seed) {
  return philoxU01(philoxDraw(key, c, kSlotSpecies).y + seed * 0x9E3779B9u);
}

vec2 seedPoint(uvec2 key, uint c, uint seed) {
  uvec2 r = philoxDraw(key, c, kSlotPosition + seed);
  return pointInStratum(clusterStratumOf(key, c), vec2(philoxU01(r.x), philoxU01(r.y)));
}

vec2 clusterCentre(uvec2 key, uint c) {
  uvec2 r = philoxDraw(key, c, kSlotCentre);
  return pointInStratum(clusterStratumOf(key, c), vec2(philoxU01(r.x), philoxU01(r.y)));
}

// vegetation::sequenceFade: a ramp over the last kSequenceFadeShare of the sequence.
const float kSequenceFadeShare = 0.25;
float sequenceFade(float count, uint index) {
  float w = count * kSequenceFadeShare > 1.0 ? count * kSequenceFadeShare : 1.0;
  return clamp((count - float(index)) / w, 0.0, 1.0);
}

uint clusterCount(float plantCount, uint clusterSize) {
  if (!(plantCount > 0.0)) return 0u;
  float c = float(clusterSize);
  return 1u + uint(ceil(max(plantCount - c, 0.0) / c));
}

float plantFade(float plantCount, uint clusterSize, uint cluster, uint seed) {
  float c = float(clusterSize);
  if (cluster == 0u) return sequenceFade(min(plantCount, c), seed);
  return sequenceFade(max(plantCount - c, 0.0) / c, cluster - 1u);
}
