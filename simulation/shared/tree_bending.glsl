// Tree branch bending and leaf flutter (issue 20): GLSL for the tree vertex shader, C++ for the
// reference (simulation/shared_code.h). Needs nothing else of the shared code.
//
// Seed ../shared/seeds/002_e402409f584e6b0c.txt §4.4–4.5, §4.7 (notes 002 §1.3–1.5).
//
// Shape. A branch bends as its fitted tapered beam, u(x) = c₂x² + c₄x⁴ with c₂ + c₄ = 1
// (vegetation/tree_bending.h, eq. 4.8), so its amplitude A is the tip deflection in branch
// lengths: u_r(x) = A_r L u(x) metres, du_r/dx̄ = A_r u′(x) (eq. 4.12).
//
// Length correction (eq. 4.9–4.11, 4.23). A purely transverse deflection stretches the branch;
// the seed moves each point back along the deflected tangent by d = (u / u′)(s − 1), s = √(1 + u′²).
// That d is the excess length of the straight line from the root to the point's tangent: exact
// for a rotated straight branch, but 1.5× the actual excess for a parabola and 1.75× for x⁴, so
// a strongly bent branch shrinks — at A = 0.5 its centre line is 7 % short for α = 0.2 (9 % for
// α = 0.1; tests/vegetation/tree_bending_test.cpp). Here the point moves back along the same
// tangent by the branch's actual excess length up to x, to first order,
//   Δ(x) = ∫₀ˣ (s − 1) dx̄ ≈ ½ ∫₀ˣ u′² dx̄ = A² L e(x),  e(x) = ⅔c₂²x³ + (8/5)c₂c₄x⁵ + (8/7)c₄²x⁷,
// a polynomial (beamExcess): the centre line keeps its length within 1 % up to A = 0.25 and
// within 2.4 % at A = 0.5 for α ≥ 0.2. Per direction the offset is o = −t Δ/s + r (u − u′ Δ/s)
// (the seed's eq. 4.11 with Δ for d: its u/s is u − u′d/s). The corrected axial coordinate for
// the tangent and normal update of eq. 4.24–4.26 is x_D = x − Δ / (s L).
//
// Wind (eq. 4.15–4.16, 4.21–4.22). A branch's amplitude is a static part, the wind's drag load
// ∝ |W| W projected on r and s (scaled so 10 m/s gives `compliance` tip deflections), plus the
// wind spectrum P_w(f) = v / (1 + f/v)^{5/3} filtered by the branch's damped oscillator, resonance
// f_h and damping ratio 0.3: four sinusoids at f_h · {0.7, 0.9, 1.1, 1.4} with amplitudes
// |H(f)| √P_w(f), a discrete stand-in for the seed's motion textures. The oscillation's RMS is
// 0.35 of the static part at 10 m/s for f_h = 1 Hz (kBranchGustGain); it grows relative to the
// static part in lighter wind (√P_w ∝ √v against the static v²), as the seed notes that
// turbulence dominates in slight to medium winds.

const float kBranchDampingRatio = 0.3f;
// 0.35 · 100 / (10 m/s · RMS of the four modes at 10 m/s, f_h = 1 Hz: 5.8889).
const float kBranchGustGain = 0.59434f;
// Leaf flutter: peak offset per m/s of wind for a card tip (3 cm at 10 m/s), capped at 25 m/s.
const float kLeafFlutterPerMps = 0.003f;
const float kLeafFlutterMaxWind = 25.0f;

// u(x) = c₂x² + c₄x⁴ (unit tip deflection when c₂ + c₄ = 1) and du/dx.
VS_INLINE float beamU(float c2, float c4, float x) {
  float x2 = x * x;
  return x2 * (c2 + c4 * x2);
}

VS_INLINE float beamDU(float c2, float c4, float x) {
  float x2 = x * x;
  return x * (2.0f * c2 + 4.0f * c4 * x2);
}

// e(x) = ½ ∫₀ˣ u′(ξ)² dξ: the first-order excess length of the deflected centre line up to x, per
// unit amplitude² and unit length.
VS_INLINE float beamExcess(float c2, float c4, float x) {
  float x2 = x * x;
  return x2 * x * (0.66666667f * c2 * c2 + x2 * (1.6f * c2 * c4 + 1.14285714f * c4 * c4 * x2));
}

// One direction's length-corrected deflection: (back along t, along the deflection direction),
// metres, for a deflection u (m), slope du (dimensionless) and excess length delta (m).
VS_INLINE vec2 beamCorrectedOffset(float u, float du, float delta) {
  float back = delta / sqrt(1.0f + du * du);
  return vec2(back, u - du * back);
}

// The offset o of the point at x ∈ [0, 1] on a branch of length L (m) and frame (t, r, s) whose
// tip is deflected by amplitude = (A_r, A_s) branch lengths: p = p_o + o.
VS_INLINE vec3 branchOffset(vec3 t, vec3 r, vec3 s, float L, float c2, float c4, float x, vec2 amplitude) {
  float u = beamU(c2, c4, x) * L;
  float du = beamDU(c2, c4, x);
  float excess = beamExcess(c2, c4, x) * L;
  vec2 onR = beamCorrectedOffset(amplitude.x * u, amplitude.x * du, amplitude.x * amplitude.x * excess);
  vec2 onS = beamCorrectedOffset(amplitude.y * u, amplitude.y * du, amplitude.y * amplitude.y * excess);
  return r * onR.y + s * onS.y - t * (onR.x + onS.x);
}

// |H(f)| of the damped oscillator with resonance fh, normalised to 1 at f = 0 (eq. 4.16).
VS_INLINE float branchResponse(float f, float fh) {
  float q = f / fh;
  float a = 1.0f - q * q;
  float b = 2.0f * kBranchDampingRatio * q;
  return 1.0f / sqrt(a * a + b * b);
}

// One mode at f = ratio · fh: its amplitude |H(f)| √P_w(f) times its sine, on r and on s.
VS_INLINE vec2 branchMode(float ratio, float phaseR, float phaseS, float fh, float v, float timeS) {
  float f = ratio * fh;
  float amplitude = branchResponse(f, fh) * sqrt(v / pow(1.0f + f / v, 1.6666667f));
  float arg = 6.2831853f * fract(f * timeS);
  return vec2(sin(arg + phaseR), sin(arg + phaseS)) * amplitude;
}

// The branch's amplitude (A_r, A_s) in branch lengths at time timeS under the wind vector `wind`
// (m/s, world) at the tree; `phase` (radians, any value) decorrelates branches.
VS_INLINE vec2 branchAmplitude(vec3 wind, vec3 r, vec3 s, float compliance, float frequencyHz, float phase,
                               float timeS) {
  float v = length(wind);
  if (v < 1e-3f) return vec2(0.0f);
  vec2 steady = vec2(dot(wind, r), dot(wind, s)) * (v * 0.01f);
  vec2 gust = branchMode(0.7f, phase, phase + 1.7f, frequencyHz, v, timeS);
  gust += branchMode(0.9f, phase * 2.618f, phase * 2.618f + 4.1f, frequencyHz, v, timeS);
  gust += branchMode(1.1f, phase * 4.236f, phase * 4.236f + 2.6f, frequencyHz, v, timeS);
  gust += branchMode(1.4f, phase * 6.854f, phase * 6.854f + 5.3f, frequencyHz, v, timeS);
  return (steady + gust * (kBranchGustGain * v * 0.01f)) * compliance;
}

// A leaf card vertex's flutter offset (m) (seed §4.7: the linear deflection u = A x of the card,
// x = weight, the vertex's `flutter` 0 at the stem … 1 at the tip): a translational flutter along
// the card's normal and a turn about its stem, sideways along normal × tangent (`tangent`: any
// direction in the card's plane, such as the branch axis it hangs on). Peak ≈ 3 cm at 10 m/s for
// weight 1. The seed's torsional mode (the card's two sides moving against each other) needs the
// vertex's side of the card, which these arguments do not carry; the sideways turn stands in.
VS_INLINE vec3 leafFlutter(vec3 normal, vec3 tangent, float weight, float frequencyHz, float phase, float windSpeed,
                           float timeS) {
  float reach = kLeafFlutterPerMps * min(windSpeed, kLeafFlutterMaxWind) * weight;
  if (!(reach > 0.0f)) return vec3(0.0f);
  vec3 side = cross(normal, tangent);
  float sideLength = length(side);
  side = sideLength > 1e-4f ? side / sideLength : vec3(0.0f);
  float a = 6.2831853f * fract(frequencyHz * timeS);
  float b = 6.2831853f * fract(1.37f * frequencyHz * timeS);
  float across = 0.6f * sin(a + phase) + 0.4f * sin(b + 2.618f * phase);
  float turn = 0.3f * sin(a + 1.9f + 4.236f * phase) + 0.2f * sin(b + 0.7f + phase);
  return (normal * across + side * turn) * reach;
}
