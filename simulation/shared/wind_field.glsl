// The one wind field (issue 19 item 1), evaluated anywhere in the world at any time: GLSL for the
// simulation pass, C++ for the reference (simulation/shared_code.h). Needs simulation_layout.glsl.
//
// Seed ../shared/seeds/004_4f0be6bef8094cc2.txt §3.2: the wind at u is a sum of three periodic noise
// textures scrolled with velocities w_i, scaled by c_i and rotated by R_i:
//   W[u] = Σ k_i T[w_i t + c_i R_i u].
// Here the noise is gradient noise on a lattice that wraps every 256 cells (the periodic texture),
// evaluated in world metres so nothing swims with the camera, and scrolled along the mean wind
// (the turbulence is carried by the flow: Taylor's frozen turbulence). Added to it:
//  - the mean wind U d;
//  - travelling gust fronts: bands across the wind, 70 m apart, moving at 1.3 U, each rising in a
//    few metres and dying away over tens (a front's strength is hashed from its index; its line
//    is bent by low-frequency noise so fronts are not straight);
//  - local sources (003 notes §1.7.5 types, extended): a fan's cone, a whirlwind's swirl (three
//    quarters around, one quarter out, as Ell's eq. 37 with the distance fall-off that the printed
//    equation lacks), and a hovering rotor's downwash (down under the hub, out along the ground,
//    weaker the higher it hovers).
// No trigonometric function is evaluated per point, so the CPU and the GPU agree to rounding.

VS_INLINE uint windHash(ivec2 c, uint salt) {
  uint h = ((uint(c.x) & 255u) * 0x8da6b343u) ^ ((uint(c.y) & 255u) * 0xd8163841u) ^ (salt * 0xcb1ab31fu);
  h ^= h >> 16u;
  h *= 0x7feb352du;
  h ^= h >> 15u;
  h *= 0x846ca68bu;
  h ^= h >> 16u;
  return h;
}

VS_INLINE vec2 windGradient(ivec2 c, uint salt) {
  uint h = windHash(c, salt);
  return vec2(float(h & 0xffffu), float(h >> 16u)) * (2.0f / 65535.0f) - vec2(1.0f);
}

// Gradient noise, quintic fade, periodic with 256 lattice cells; about −1 … 1.
VS_INLINE float windNoise(vec2 q, uint salt) {
  vec2 f = floor(q);
  ivec2 i = ivec2(int(f.x), int(f.y));
  vec2 r = q - f;
  vec2 u = r * r * r * (r * (r * 6.0f - vec2(15.0f)) + vec2(10.0f));
  float n00 = dot(windGradient(i, salt), r);
  float n10 = dot(windGradient(i + ivec2(1, 0), salt), r - vec2(1.0f, 0.0f));
  float n01 = dot(windGradient(i + ivec2(0, 1), salt), r - vec2(0.0f, 1.0f));
  float n11 = dot(windGradient(i + ivec2(1, 1), salt), r - vec2(1.0f, 1.0f));
  return 1.4f * mix(mix(n00, n10, u.x), mix(n01, n11, u.x), u.y);
}

// Layer i of the turbulence (seed eq. of §3.2): scale 48, 16, 6 m; amplitude 0.45, 0.30, 0.18 of
// the mean speed times the gustiness; scrolled at 1.0, 1.2, 1.45 times the mean wind; each layer's
// lattice turned by 0, 0.7, 1.9 rad (cos and sin written out, so C++ and GLSL use the same values).
VS_INLINE vec2 windLayer(int i, vec2 p, vec2 mean, float gust, float t) {
  float scale = i == 0 ? 48.0f : (i == 1 ? 16.0f : 6.0f);
  float amp = i == 0 ? 0.45f : (i == 1 ? 0.30f : 0.18f);
  float scroll = i == 0 ? 1.0f : (i == 1 ? 1.2f : 1.45f);
  float c = i == 0 ? 1.0f : (i == 1 ? 0.76484219f : -0.32328957f);
  float s = i == 0 ? 0.0f : (i == 1 ? 0.64421769f : 0.94630009f);
  vec2 a = p - mean * (scroll * t);
  vec2 q = vec2(c * a.x - s * a.y, s * a.x + c * a.y) * (1.0f / scale);
  float k = amp * gust * length(mean);
  uint salt = uint(2 * i);
  return vec2(windNoise(q, salt), windNoise(q + vec2(17.31f, 41.73f), salt + 1u)) * k;
}

// Gust fronts across the mean wind (see above).
VS_INLINE vec2 windGusts(vec2 p, vec2 mean, float gust, float t) {
  float speed = length(mean);
  if (speed < 0.01f || gust <= 0.0f) return vec2(0.0f);
  vec2 d = mean / speed;
  float along = dot(p, d) - 1.3f * speed * t;
  float across = dot(p, vec2(-d.y, d.x));
  float phase = along * (1.0f / 70.0f) + 0.35f * windNoise(vec2(across * (1.0f / 120.0f), along * (1.0f / 400.0f)), 7u);
  float idx = floor(phase);
  float phi = phase - idx;
  // A point meets a front at φ → 1 first (φ falls as the band passes): a sharp rise, a slow fall.
  float bump = smoothstep(0.45f, 0.92f, phi) * (1.0f - smoothstep(0.92f, 1.0f, phi));
  float strength = 0.5f + 0.5f * float(windHash(ivec2(int(idx), 0), 9u) & 0xffffu) * (1.0f / 65535.0f);
  return d * (1.1f * gust * speed * strength * bump);
}

VS_INLINE vec3 sourceWind(WindSourceGpu s, vec2 p) {
  vec2 r = p - vec2(s.position.x, s.position.y);
  float dist = length(r);
  float radius = s.position.w;
  float strength = s.params.y;
  int type = int(s.params.x + 0.5f);
  if (!(dist < radius) || radius <= 0.0f) return vec3(0.0f);
  float fall = 1.0f - dist / radius;
  vec2 radial = dist > 1e-3f ? r / dist : vec2(0.0f);
  if (type == kSourceFan) {
    vec2 d = vec2(s.params.z, s.params.w);
    float cone = smoothstep(0.80f, 0.95f, dot(radial, d));  // about 25° half-angle
    return vec3(d * (strength * fall * cone), 0.0f);
  }
  if (type == kSourceWhirlwind) {
    vec2 around = vec2(-radial.y, radial.x);
    float eye = min(dist / (0.2f * radius), 1.0f);  // calm at the centre
    return vec3((around * 0.75f + radial * 0.25f) * (strength * fall * eye), 0.0f);
  }
  if (type == kSourceRotor) {
    float ground = clamp(1.0f - s.position.z / (4.0f * radius), 0.0f, 1.0f);  // weaker the higher it hovers
    float x = dist / radius;
    float outflow = 4.0f * x * fall;  // 0 under the hub, 1 half-way out, 0 at the rim
    return vec3(radial * (strength * ground * outflow), -strength * ground * (1.0f - x * x));
  }
  return vec3(0.0f);
}

// The wind (m/s, world axes, z up) at world point p (ground level) and time t.
VS_INLINE vec3 windAt(VS_SIM_ARG vec2 p, float t) {
  vec2 mean = vec2(sim.wind.x, sim.wind.y);
  float gust = sim.wind.z;
  vec2 w = mean;
  for (int i = 0; i < 3; ++i) w += windLayer(i, p, mean, gust, t);
  w += windGusts(p, mean, gust, t);
  vec3 total = vec3(w.x, w.y, 0.0f);
  for (int i = 0; i < sim.counts.x; ++i) total += sourceWind(sim.sources[i], p);
  return total;
}
