// The one triangle an impostor is drawn on (tree_impostor_outline.h).
#include "render/tree_impostor_outline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace vegstream::render {

glm::vec2 impostorQuadHalf(const ImpostorQuadShape& q, float sinE) {
  const float cosE = std::sqrt(std::max(0.0f, 1.0f - sinE * sinE));
  const float rc = 1.08f * q.crownRadiusM, hh = 0.55f * q.heightM;
  return {std::min(rc, q.halfExtentM), std::min(hh * cosE + rc * sinE, q.halfExtentM)};
}

ImpostorTriangle impostorTriangle(std::span<const vegetation::TreeVertex> vertices, const ImpostorQuadShape& q) {
  constexpr int kElevations = 9, kYaws = 64, kBuckets = 256, kApexSteps = 64;
  constexpr float kMargin = 0.03f;
  float cosPhi[kYaws], sinPhi[kYaws];
  for (int a = 0; a < kYaws; ++a) {
    // The yaw's sampling moves a point by at most ρ · 2.5 %: inside the margin.
    const float phi = 6.2831853f * (float(a) + 0.5f) / float(kYaws);
    cosPhi[a] = std::abs(std::cos(phi));
    sinPhi[a] = std::sin(phi);
  }
  // What a vertex sweeps over all yaws is an ellipse about (0, (z − centre) cos E), semi-axes ρ
  // and ρ sin E: those of one height are nested, so the widest vertex of each centimetre of
  // height stands for the rest (tens of thousands of vertices → a few hundred rings).
  std::map<int, float> widestAt;
  for (const vegetation::TreeVertex& v : vertices) {
    float& rho = widestAt[static_cast<int>(std::lround(v.position[2] * 100.0f))];
    rho = std::max(rho, std::hypot(v.position[0], v.position[1]));
  }
  ImpostorTriangle out;
  for (int bin = 0; bin < 4; ++bin) {
    // The widest x (a share of X, with the margin) in each band of `up`, over the bin's views
    // and every yaw; what lies outside the rectangle is not drawn (it never was).
    std::array<float, kBuckets> widest{};
    for (int e = 0; e < kElevations; ++e) {
      const float sinE = std::min(1.0f, 0.25f * (float(bin) + float(e) / float(kElevations - 1)));
      const float cosE = std::sqrt(std::max(0.0f, 1.0f - sinE * sinE));
      const glm::vec2 half = impostorQuadHalf(q, sinE);
      if (half.x <= 0.0f || half.y <= 0.0f) continue;
      for (const auto& [cm, rho] : widestAt) {
        const float dz = (float(cm) * 0.01f - q.centreZ) * cosE;
        for (int a = 0; a < kYaws; ++a) {
          const float y = dz - rho * sinPhi[a] * sinE;
          if (y <= -half.y || y >= half.y) continue;
          const float x = std::min(1.0f, rho * cosPhi[a] / half.x * (1.0f + kMargin) + kMargin);
          const auto k = std::min(kBuckets - 1, static_cast<int>((y + half.y) / (2.0f * half.y) * kBuckets));
          widest[size_t(k)] = std::max(widest[size_t(k)], x);
        }
      }
    }
    // For each apex height a ≥ 1 the narrowest base: x ≤ b (a − up) / a at each band's top edge.
    float best = 1e30f;
    for (int s = 0; s <= kApexSteps; ++s) {
      const float a = 1.0f + 3.0f * float(s) / float(kApexSteps);
      float b = 0.0f;
      for (int i = 0; i < kBuckets; ++i)
        if (widest[size_t(i)] > 0.0f) b = std::max(b, widest[size_t(i)] * a / (a - float(i + 1) / kBuckets));
      if (b <= 0.0f) b = 1.0f;  // nothing in view: any triangle
      if (a * b < best) {
        best = a * b;
        out.apex[bin] = a;
        out.base[bin] = b;
      }
    }
  }
  return out;
}

}  // namespace vegstream::render
