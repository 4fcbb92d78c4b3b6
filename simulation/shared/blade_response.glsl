// A drawn blade's response to the shared simulation (issue 19 items 2–3): GLSL for both blade
// paths (shaders/common/plant_params.glsl), C++ for the reference (simulation/shared_code.h).
// Needs simulation_layout.glsl and virtual_blade.glsl.
//
// Wind. Seed 004 §3.3: each drawn blade solves its static equilibrium under the moments of the
// virtual blade of its wind cell, k ψ_i = m_i + (torque of gravity on the part above), by simple
// iteration (the seed finds three enough; two here, starting from the rest shape). Drawn blades
// keep their solved rest shape (core seed 001 §2.3: root tilt, droop under their own weight) and
// the wind bends it: hinge i at x_i = i / kBladeHinges of the length turns the part above it by
// δ_i, where
//   δ_i = (s_ref / s) m̂_i + ΔQ_i(δ) / k̂,
// m̂_i the stored moment (the reference blade's equivalent lean), s the blade's relative
// stiffness, k̂ = 4 s / 7.837 its hinge spring in units of its weight × length, and ΔQ_i the
// change of gravity's torque on the part above hinge i between the bent and the rest shape (a
// soft blade pushed over sags further). No wind: δ = 0 and the rest shape is drawn exactly.
//
// Interaction. The interaction field's strength cs under the root flattens the blade towards the
// field's bend direction: a turn of kMaxFlattenRad · F about the root, F = 1 − (1 − min(cs / s, 1))³
// (Orthmann's cubic recovery, 000 notes §5.6: a hard hit holds the blade down, then it springs up).
// cs decays linearly at the recovery rate (Ell eq. 47), so harder hits take longer.
//
// Colliders. Whatever the field says, a blade whose tip ends inside a collider of this frame is
// turned further about its root, away from the collider's axis, until the tip is out (bisection):
// no tip is ever drawn inside a collider (a collider resting on the ground still covers the
// blades rooted under it).

const float kMaxFlattenRad = 1.35f;
const float kGrassReachM = 0.8f;  // the height of the layer colliders press into
const float kRecoveryPerS = 0.1f; // cs units per second (Ell eq. 47's c_r)

// Rotates v about a horizontal axis so that ẑ tilts towards `lean` by |lean| (Rodrigues).
VS_INLINE vec3 leanRotate(vec3 v, vec2 lean) {
  float a = length(lean);
  if (a < 1e-6f) return v;
  vec3 axis = vec3(-lean.y / a, lean.x / a, 0.0f);
  float c = cos(a), s = sin(a);
  return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1.0f - c));
}

// The rest shape where the hinges act, relative to the root, unit length, world-oriented: the
// hinge points (x_i = i / kBladeHinges; hinge 0 is the root) and the segment centres.
struct BladeRest {
  vec3 hinge[kBladeHinges];
  vec3 centre[kBladeHinges];
};

// A turn about the root as a unit quaternion (xyz, w): the flattening and the colliders' turns
// compose, and a collider may need a turn about any axis.
VS_INLINE vec4 leanQuat(vec2 lean) {
  float a = length(lean);
  if (a < 1e-6f) return vec4(0.0f, 0.0f, 0.0f, 1.0f);
  float s = sin(0.5f * a) / a;
  return vec4(-lean.y * s, lean.x * s, 0.0f, cos(0.5f * a));
}

VS_INLINE vec4 quatMul(vec4 a, vec4 b) {
  vec3 av = vec3(a.x, a.y, a.z), bv = vec3(b.x, b.y, b.z);
  vec3 v = bv * a.w + av * b.w + cross(av, bv);
  return vec4(v.x, v.y, v.z, a.w * b.w - dot(av, bv));
}

VS_INLINE vec3 quatRotate(vec4 q, vec3 v) {
  vec3 u = vec3(q.x, q.y, q.z);
  vec3 t = cross(u, v) * 2.0f;
  return v + t * q.w + cross(u, t);
}

// The turn taking unit `from` a fraction t of the way to unit `to` (about their common normal).
VS_INLINE vec4 turnQuat(vec3 from, vec3 to, float t) {
  vec3 axis = cross(from, to);
  float s = length(axis);
  if (s < 1e-6f) return vec4(0.0f, 0.0f, 0.0f, 1.0f);
  float halfAngle = 0.5f * t * atan(s, dot(from, to));
  axis *= sin(halfAngle) / s;
  return vec4(axis.x, axis.y, axis.z, cos(halfAngle));
}

struct BladeBend {
  vec2 hinge[kBladeHinges];  // δ_i
  vec4 root;                 // the flattening and collider turns about the root (a quaternion), applied last
  float moving;              // 0: the rest shape (nothing to apply)
};

// A point at fraction x of the blade (its rest position `p` relative to the root, unit length) as
// the bend moves it: hinges from the tip down, each about its rest point (lower turns then carry
// it), then the root turn.
VS_INLINE vec3 bendPoint(BladeBend b, BladeRest r, vec3 p, float x) {
  for (int i = kBladeHinges - 1; i >= 0; --i)
    if (x > float(i) / float(kBladeHinges) && dot(b.hinge[i], b.hinge[i]) > 0.0f)
      p = r.hinge[i] + leanRotate(p - r.hinge[i], b.hinge[i]);
  return quatRotate(b.root, p);
}

// A direction along the blade at fraction x (a normal or side vector).
VS_INLINE vec3 bendVector(BladeBend b, vec3 v, float x) {
  for (int i = kBladeHinges - 1; i >= 0; --i)
    if (x >= float(i) / float(kBladeHinges)) v = leanRotate(v, b.hinge[i]);
  return quatRotate(b.root, v);
}

// ΔQ_i / (weight × length): gravity's torque on the part above hinge i, bent minus rest.
VS_INLINE vec2 gravityChange(BladeBend b, BladeRest r, int i) {
  BladeBend hinges = b;
  hinges.root = vec4(0.0f, 0.0f, 0.0f, 1.0f);
  vec3 h = bendPoint(hinges, r, r.hinge[i], float(i) / float(kBladeHinges));
  vec2 q = vec2(0.0f);
  for (int j = i; j < kBladeHinges; ++j) {
    vec3 c = bendPoint(hinges, r, r.centre[j], (float(j) + 0.5f) / float(kBladeHinges));
    vec3 bent = c - h, rest = r.centre[j] - r.hinge[i];
    q += (vec2(bent.x, bent.y) - vec2(rest.x, rest.y)) * (1.0f / float(kBladeHinges));
  }
  return q;
}

VS_INLINE BladeBend solveBladeBend(BladeRest r, BladeMoments m, float relativeStiffness) {
  BladeBend b;
  b.root = vec4(0.0f, 0.0f, 0.0f, 1.0f);
  b.moving = 1.0f;
  float s = max(relativeStiffness, 0.3f);
  float kHat = 4.0f * s / kElasticaBuckling;
  for (int i = 0; i < kBladeHinges; ++i) b.hinge[i] = m.m[i] * (kRefStiffness / s);
  for (int it = 0; it < 2; ++it)
    for (int i = 0; i < kBladeHinges; ++i) {
      vec2 d = m.m[i] * (kRefStiffness / s) + gravityChange(b, r, i) / kHat;
      float a = length(d);
      b.hinge[i] = a > kMaxLean ? d * (kMaxLean / a) : d;
    }
  return b;
}

// The interaction field's turn for a texel (xy: bend direction, z: strength cs).
VS_INLINE vec2 flattenLean(vec4 texel, float relativeStiffness) {
  float u = min(max(texel.z, 0.0f) / max(relativeStiffness, 0.3f), 1.0f);
  float f = 1.0f - (1.0f - u) * (1.0f - u) * (1.0f - u);
  vec2 d = vec2(texel.x, texel.y);
  float len = length(d);
  return len > 1e-4f ? d * (kMaxFlattenRad * f / len) : vec2(0.0f);
}

// Distance (m) from p to a collider's solid: a capsule with a vertical axis of half-length `half`
// (0: a sphere); negative inside.
VS_INLINE float colliderDistance(vec3 centre, float radius, float halfAxis, vec3 p) {
  vec3 d = p - centre;
  d.z -= clamp(d.z, -halfAxis, halfAxis);
  return length(d) - radius;
}

// The root turn that takes the tip out of the colliders: `tip` relative to the root (metres, bent
// by the wind), `root` camera-relative, `turn` the turn so far (the flattening). For each collider
// the tip is inside of, the smallest fraction (bisection, to 1e-3) of the turn that lays the tip
// down flat, away from the collider's axis, that clears it; the whole turn when none does (a
// flat tip is outside any collider that does not sink into the ground).
VS_INLINE vec4 colliderTurn(VS_SIM_ARG vec3 root, vec3 tip, vec4 turn) {
  for (int c = 0; c < sim.counts.y; ++c) {
    ColliderGpu k = sim.colliders[c];
    vec3 centre = vec3(k.centre.x, k.centre.y, k.centre.z);
    vec3 now = quatRotate(turn, tip);
    if (colliderDistance(centre, k.centre.w, k.shape.x, root + now) >= 0.0f) continue;
    vec2 away = vec2(root.x - centre.x, root.y - centre.y);
    float len = length(away);
    away = len > 1e-4f ? away / len : vec2(1.0f, 0.0f);
    vec3 from = normalize(now), to = normalize(vec3(away.x, away.y, 0.05f));
    float lo = 0.0f, hi = 1.0f;
    for (int it = 0; it < 10; ++it) {
      float mid = 0.5f * (lo + hi);
      if (colliderDistance(centre, k.centre.w, k.shape.x, root + quatRotate(turnQuat(from, to, mid), now)) >= 0.0f)
        hi = mid;
      else
        lo = mid;
    }
    turn = quatMul(turnQuat(from, to, hi), turn);
  }
  return turn;
}

// How far a collider presses into the grass layer over a texel (0 … 1): the layer is the
// kGrassReachM above the ground under the collider; the collider swept from its previous centre
// (`previous`, when shape.w is 1) to its centre over the frame, so a fast one leaves no gaps.
VS_INLINE float colliderPress(ColliderGpu k, vec2 texel) {
  vec2 a = vec2(k.centre.x, k.centre.y);
  vec2 b = k.shape.w > 0.5f ? vec2(k.previous.x, k.previous.y) : a;
  vec2 ab = b - a;
  float t = dot(ab, ab) > 1e-8f ? clamp(dot(texel - a, ab) / dot(ab, ab), 0.0f, 1.0f) : 0.0f;
  float d = length(texel - (a + ab * t));
  float radius = k.centre.w;
  if (d >= radius) return 0.0f;
  float bottom = k.centre.z - k.shape.x - sqrt(radius * radius - d * d);
  return clamp((k.shape.y + kGrassReachM - bottom) / kGrassReachM, 0.0f, 1.0f);
}

// One frame of an interaction texel (xy: bend direction, z: cs) at camera-relative `texel`:
// the linear recovery (this frame's decay and, for a tile just restored from the trail store,
// what it missed), then every collider's press. A harder press replaces the direction: grass
// is pushed along the collider's motion and out from its path.
VS_INLINE vec4 interactionStep(VS_SIM_ARG vec4 value, vec2 texel, float extraDecay) {
  float cs = max(value.z - sim.field.z - extraDecay, 0.0f);
  vec2 dir = vec2(value.x, value.y);
  for (int c = 0; c < sim.counts.y; ++c) {
    ColliderGpu k = sim.colliders[c];
    float press = colliderPress(k, texel);
    float hit = press * k.shape.z;
    if (hit <= cs) continue;
    vec2 centre = vec2(k.centre.x, k.centre.y);
    vec2 motion = k.shape.w > 0.5f ? centre - vec2(k.previous.x, k.previous.y) : vec2(0.0f);
    vec2 away = texel - centre;
    if (length(motion) > 1e-3f) {
      vec2 m = normalize(motion);
      away -= m * dot(away, m);  // out from the path, not back along it
      dir = m * 1.5f + (length(away) > 1e-3f ? normalize(away) : vec2(0.0f));
    } else {
      dir = length(away) > 1e-3f ? away : vec2(1.0f, 0.0f);
    }
    dir = normalize(dir);
    cs = hit;
  }
  return vec4(dir.x, dir.y, cs, 0.0f);
}
