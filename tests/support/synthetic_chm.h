#pragma once
// A synthetic canopy height model made from a known list of trees, and the matching of detected
// trees against that list (issue 41 item 3: vegetation/crown_detection.h and the import's canopy
// layer are tested with it).
//
// Trees: `count` of them in a square of sideM metres (a margin of 10 m kept free), half in
// Neyman–Scott clumps (parents uniform, children normal about them, σ 5 m), half uniform; heights
// uniform in 5 … 35 m; crown radius from the allometry r = 0.6 + 0.1 h times a log-normal
// spread (σ 0.15); a crown is a paraboloid (depth 0.6 h) or a flat half-ellipsoid (depth 0.4 h),
// one in two. Only trees whose top can be seen are kept: a candidate is drawn again when it
// stands closer than 2.5 m to another tree, or when its top is not 1 m above the other crowns
// within 1.5 m of it (the matching's distance), or it reaches so near another's top — close
// neighbours whose tops stick out stay, as in a stand; a top on another crown's shoulder is no
// local maximum of any CHM and is not drawn.
// The CHM: the highest crown over each pixel centre (0 on open ground) plus normal noise σ,
// pixel (col, row) centred at x = (col + 0.5) pixelM, y = (row + 0.5) pixelM (row 0 at y = 0).

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace vegstream::testing {

struct TrueTree {
  double x = 0.0, y = 0.0;
  float heightM = 0.0f, radiusM = 0.0f;
  bool paraboloid = true;
};

// The tree's crown surface at horizontal distance d from its axis; -inf outside the crown.
inline float crownSurface(const TrueTree& t, double d) {
  if (d > t.radiusM) return -INFINITY;
  const double u = d / t.radiusM;
  if (t.paraboloid) return static_cast<float>(t.heightM - 0.6 * t.heightM * u * u);
  const double depth = 0.4 * t.heightM;
  return static_cast<float>(t.heightM - depth + depth * std::sqrt(std::max(0.0, 1.0 - u * u)));
}

inline bool visibleWith(const TrueTree& c, const std::vector<TrueTree>& trees) {
  for (const TrueTree& t : trees) {
    const double d = std::hypot(c.x - t.x, c.y - t.y);
    if (d < 2.5) return false;
    const double near = std::max(0.0, d - 1.5);
    if (crownSurface(t, near) > c.heightM - 1.0f || crownSurface(c, near) > t.heightM - 1.0f) return false;
  }
  return true;
}

inline std::vector<TrueTree> syntheticTrees(int count, double sideM, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(10.0, sideM - 10.0);
  std::uniform_real_distribution<float> height(5.0f, 35.0f);
  std::normal_distribution<double> clump(0.0, 5.0);
  std::normal_distribution<float> spread(0.0f, 0.15f);
  std::vector<std::pair<double, double>> parents;
  for (int i = 0; i < std::max(1, count / 12); ++i) parents.emplace_back(pos(rng), pos(rng));
  std::vector<TrueTree> trees;
  for (int attempts = 0; int(trees.size()) < count && attempts < 200000; ++attempts) {
    TrueTree t;
    if (trees.size() % 2 == 0) {
      const auto& p = parents[static_cast<size_t>(rng() % parents.size())];
      t.x = std::clamp(p.first + clump(rng), 10.0, sideM - 10.0);
      t.y = std::clamp(p.second + clump(rng), 10.0, sideM - 10.0);
    } else {
      t.x = pos(rng);
      t.y = pos(rng);
    }
    t.heightM = height(rng);
    t.radiusM = (0.6f + 0.1f * t.heightM) * std::exp(spread(rng));
    t.paraboloid = (rng() & 1u) != 0;
    if (visibleWith(t, trees)) trees.push_back(t);
  }
  return trees;
}

// The CHM of `trees` on a side × side grid of pixelM pixels (row 0 at y = 0), noise σ noiseM.
inline std::vector<float> rasterizeChm(const std::vector<TrueTree>& trees, int side, double pixelM, float noiseM,
                                       uint32_t seed) {
  std::vector<float> chm(size_t(side) * size_t(side), 0.0f);
  for (const TrueTree& t : trees) {
    const int c0 = std::max(0, int((t.x - t.radiusM) / pixelM)), c1 = std::min(side - 1, int((t.x + t.radiusM) / pixelM));
    const int r0 = std::max(0, int((t.y - t.radiusM) / pixelM)), r1 = std::min(side - 1, int((t.y + t.radiusM) / pixelM));
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c) {
        const double d = std::hypot((c + 0.5) * pixelM - t.x, (r + 0.5) * pixelM - t.y);
        float& v = chm[size_t(r) * size_t(side) + size_t(c)];
        v = std::max(v, crownSurface(t, d));
      }
  }
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, noiseM);
  for (float& v : chm) v += noise(rng);
  return chm;
}

struct FoundTree {
  double x = 0.0, y = 0.0;
  float heightM = 0.0f;
};

struct MatchFigures {
  int truth = 0, found = 0, matched = 0;
  double recall = 0.0, extraShare = 0.0, heightRmsM = 0.0, positionRmsM = 0.0;
};

// Greedy one-to-one matching, tallest true tree first, each to the nearest unmatched found tree
// within maxDistanceM.
inline MatchFigures matchTrees(std::vector<TrueTree> truth, const std::vector<FoundTree>& found, double maxDistanceM) {
  std::sort(truth.begin(), truth.end(), [](const TrueTree& a, const TrueTree& b) { return a.heightM > b.heightM; });
  std::vector<bool> used(found.size(), false);
  MatchFigures m;
  m.truth = int(truth.size());
  m.found = int(found.size());
  double h2 = 0.0, p2 = 0.0;
  for (const TrueTree& t : truth) {
    int best = -1;
    double bestD = maxDistanceM;
    for (size_t i = 0; i < found.size(); ++i) {
      const double d = std::hypot(found[i].x - t.x, found[i].y - t.y);
      if (!used[i] && d <= bestD) best = int(i), bestD = d;
    }
    if (best < 0) continue;
    used[size_t(best)] = true;
    ++m.matched;
    h2 += std::pow(double(found[size_t(best)].heightM - t.heightM), 2);
    p2 += bestD * bestD;
  }
  m.recall = m.truth ? double(m.matched) / m.truth : 0.0;
  m.extraShare = m.truth ? double(m.found - m.matched) / m.truth : 0.0;
  m.heightRmsM = m.matched ? std::sqrt(h2 / m.matched) : 0.0;
  m.positionRmsM = m.matched ? std::sqrt(p2 / m.matched) : 0.0;
  return m;
}

}  // namespace vegstream::testing
