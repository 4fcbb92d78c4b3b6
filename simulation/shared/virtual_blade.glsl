// The virtually-inertial blade model, seed ../shared/seeds/004_4f0be6bef8094cc2.txt §3.1–3.3
// (issue 19 item 2). GLSL for the simulation pass, C++ for the reference (simulation/shared_code.h).
// Needs simulation_layout.glsl.
//
// One virtual blade stands at the centre of each wind cell: the reference grass blade (0.5 m,
// 0.2 g, stiffness 2.5 k_c) cut into kBladeHinges segments, each hinge a spring. Its state is the
// lean ψ_i of each hinge (a horizontal rotation vector: ẑ tilts towards ψ by |ψ|) and its rate ω_i.
// §3.1's simplified algorithm integrates J ω̇_i = −k ψ_i + (external torque) per hinge without the
// second Featherstone pass. Two departures, both for a blade that behaves like grass at any frame
// rate:
//  - a hinge carries the inertia and the loads of every segment above it, each at its lever
//    (with the §3.1 simplification — each hinge alone — the root swings at the tip's 8 Hz; lumped
//    it swings near 1 Hz, as grass does);
//  - a little structural damping (20 % of critical) on top of the aerodynamic damping that §3.2's
//    relative velocity already gives; fixed sub-steps of kSubstepS, semi-implicit Euler.
// Forces act at the segments' centres: weight, and drag f = k_w |W − v|^(γ−1) (W − v) (§3.2,
// γ = 4/3) on the part of the relative wind across the segment, W taken at blade height (a
// canopy factor on the 10 m wind, rising along the blade).
//
// §3.3: the moment each hinge must carry for the blade to hold its current shape in static
// equilibrium is m_i = k ψ_i − (torque of gravity on the part above). Drawn blades
// (blade_response.glsl) solve their own equilibrium under m_i with their own stiffness and rest
// shape. The moments are stored as the reference blade's equivalent lean m_i / k (rad).

const float kRefBladeLengthM = 0.5f;
const float kRefBladeMassKg = 2.0e-4f;
const float kRefStiffness = 2.5f;  // k′ / k_c as the catalog gives stiffness: stiffer than most grass, so
                                   // its rest solve converges and its moments are mostly the wind's
const float kGravity = 9.81f;
// λ_max of a continuous blade under its own weight: k_c(N) / N³ → 1 / 7.837 (vegetation/blade_shape.h).
const float kElasticaBuckling = 7.837f;
const float kDragPerSegment = 1.5e-5f;  // k_w: ½ ρ C_d × width × segment length, N / (m/s)^γ
const float kDragExponent = 1.33333333f;
const float kCanopyWind = 0.45f;        // wind at the blade's foot relative to the 10 m wind
const float kStructuralDamping = 0.2f;  // fraction of critical damping per hinge
const float kMaxLean = 1.5f;            // rad per hinge: the state never leaves a sane range

// The hinge's spring (N m / rad): the reference blade's k′ = s k_c for a chain of kBladeHinges.
VS_INLINE float hingeStiffness(float relativeStiffness) {
  return 4.0f * relativeStiffness * kRefBladeMassKg * kGravity * kRefBladeLengthM / kElasticaBuckling;
}

// Unit direction of a segment leaning by τ (ẑ tilted towards τ by |τ|).
VS_INLINE vec3 leanDirection(vec2 tau) {
  float a = length(tau);
  float sinc = a > 1e-4f ? sin(a) / a : 1.0f;
  return vec3(tau.x * sinc, tau.y * sinc, cos(a));
}

// A torque (about a horizontal axis) as the generalised force on a lean: rotation about +y tilts
// ẑ towards +x, so Q = (τ_y, −τ_x).
VS_INLINE vec2 leanTorque(vec3 lever, vec3 force) {
  vec3 t = cross(lever, force);
  return vec2(t.y, -t.x);
}

struct VirtualBlade {
  vec2 lean[kBladeHinges];  // ψ_i
  vec2 rate[kBladeHinges];  // ω_i
};

struct BladeChain {
  vec3 hinge[kBladeHinges];   // hinge points, the root first at 0
  vec3 centre[kBladeHinges];  // segment centres
  vec3 dir[kBladeHinges];     // segment directions
  vec2 tauRate[kBladeHinges]; // Σ_{k≤j} ω_k: each segment's lean rate
};

VS_INLINE BladeChain virtualChain(VirtualBlade b) {
  BladeChain c;
  float h = kRefBladeLengthM / float(kBladeHinges);
  vec2 tau = vec2(0.0f), tauRate = vec2(0.0f);
  vec3 at = vec3(0.0f);
  for (int j = 0; j < kBladeHinges; ++j) {
    tau += b.lean[j];
    tauRate += b.rate[j];
    vec3 u = leanDirection(tau);
    c.hinge[j] = at;
    c.dir[j] = u;
    c.centre[j] = at + u * (0.5f * h);
    c.tauRate[j] = tauRate;
    at += u * h;
  }
  return c;
}

// The segment's force: weight, and (when `wind`) drag from the wind W at its height.
VS_INLINE vec3 segmentForce(BladeChain c, int j, vec3 wind, bool withWind) {
  float h = kRefBladeLengthM / float(kBladeHinges);
  vec3 f = vec3(0.0f, 0.0f, -kGravity * kRefBladeMassKg / float(kBladeHinges));
  if (!withWind) return f;
  // The centre's velocity: the segments below swing it by h each, its own by h / 2.
  vec2 v = c.tauRate[j] * (0.5f * h);
  for (int k = 0; k < j; ++k) v += c.tauRate[k] * h;
  float height = (float(j) + 0.5f) / float(kBladeHinges);
  vec3 rel = wind * (kCanopyWind * (0.6f + 0.4f * height)) - vec3(v.x, v.y, 0.0f);
  vec3 across = rel - c.dir[j] * dot(c.dir[j], rel);
  float speed = length(across);
  return f + across * (kDragPerSegment * pow(max(speed, 1e-6f), kDragExponent - 1.0f));
}

// Generalised force on hinge i from the segments above it (gravity alone unless `withWind`).
VS_INLINE vec2 hingeLoad(BladeChain c, int i, vec3 wind, bool withWind) {
  vec2 q = vec2(0.0f);
  for (int j = i; j < kBladeHinges; ++j) q += leanTorque(c.centre[j] - c.hinge[i], segmentForce(c, j, wind, withWind));
  return q;
}

// Hinge i's lumped inertia: every segment above it, a rod about its own centre plus its lever.
VS_INLINE float hingeInertia(int i) {
  float h = kRefBladeLengthM / float(kBladeHinges);
  float m = kRefBladeMassKg / float(kBladeHinges);
  float j = 0.0f;
  for (int k = i; k < kBladeHinges; ++k) {
    float d = (float(k - i) + 0.5f) * h;
    j += m * (h * h / 12.0f + d * d);
  }
  return j;
}

// One sub-step of dt under the wind W (m/s) at the blade's cell.
VS_INLINE void virtualBladeStep(VS_INOUT(VirtualBlade) b, vec3 wind, float dt) {
  float k = hingeStiffness(kRefStiffness);
  BladeChain c = virtualChain(b);
  for (int i = 0; i < kBladeHinges; ++i) {
    float inertia = hingeInertia(i);
    float damping = 2.0f * kStructuralDamping * sqrt(k * inertia);
    vec2 torque = hingeLoad(c, i, wind, true) - b.lean[i] * k - b.rate[i] * damping;
    b.rate[i] += torque * (dt / inertia);
  }
  for (int i = 0; i < kBladeHinges; ++i) {
    b.lean[i] += b.rate[i] * dt;
    float a = length(b.lean[i]);
    if (a > kMaxLean) {
      b.lean[i] *= kMaxLean / a;
      b.rate[i] = vec2(0.0f);
    }
  }
}

// The blade at rest under a steady wind W: the static equilibrium k ψ_i = Q_i(ψ) by fixed-point
// iteration from upright (a cell entering the window starts here instead of upright, so new
// cells do not spring up as the camera moves).
VS_INLINE VirtualBlade virtualBladeAtRest(vec3 wind) {
  VirtualBlade b;
  for (int i = 0; i < kBladeHinges; ++i) {
    b.lean[i] = vec2(0.0f);
    b.rate[i] = vec2(0.0f);
  }
  float k = hingeStiffness(kRefStiffness);
  for (int it = 0; it < 12; ++it) {
    BladeChain c = virtualChain(b);
    for (int i = 0; i < kBladeHinges; ++i) {
      vec2 lean = hingeLoad(c, i, wind, true) / k;
      float a = length(lean);
      b.lean[i] = a > kMaxLean ? lean * (kMaxLean / a) : lean;
    }
  }
  return b;
}

// §3.3's moments, as the reference blade's equivalent lean (rad): m_i / k = ψ_i − Q_gravity,i / k.
struct BladeMoments {
  vec2 m[kBladeHinges];
};

VS_INLINE BladeMoments virtualBladeMoments(VirtualBlade b) {
  float k = hingeStiffness(kRefStiffness);
  BladeChain c = virtualChain(b);
  BladeMoments r;
  for (int i = 0; i < kBladeHinges; ++i) r.m[i] = b.lean[i] - hingeLoad(c, i, vec3(0.0f), false) / k;
  return r;
}

// Kinetic plus spring energy (J): bounded under a bounded wind (the stability test).
VS_INLINE float virtualBladeEnergy(VirtualBlade b) {
  float k = hingeStiffness(kRefStiffness);
  float e = 0.0f;
  for (int i = 0; i < kBladeHinges; ++i)
    e += 0.5f * hingeInertia(i) * dot(b.rate[i], b.rate[i]) + 0.5f * k * dot(b.lean[i], b.lean[i]);
  return e;
}
