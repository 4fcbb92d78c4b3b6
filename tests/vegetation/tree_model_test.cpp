// vegetation/tree_model.h: the procedural tree models of issue 20 — deterministic per seed, a
// consistent branch hierarchy (seed ../shared/seeds/002_e402409f584e6b0c.txt §4.3: every
// vertex's branch and x, every branch starting on its parent's axis), a mesh inside the asked
// height and crown, and a Reduced level of detail with a quarter of the triangles and the same
// silhouette.

#include <algorithm>
#include <map>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include "vegetation/species_catalog.h"
#include "vegetation/tree_bending.h"
#include "vegetation/tree_model.h"

namespace vegstream::vegetation {
namespace {

using glm::vec3;

struct Species {
  const char* name;
  TreeParams params;
  float heightM, crownM;
};

TreeParams conifer(uint32_t levels) {
  TreeParams p;
  p.form = TreeForm::Conifer;
  p.branchLevels = levels;
  return p;
}

TreeParams broadleaf(uint32_t levels) {
  TreeParams p;
  p.form = TreeForm::Broadleaf;
  p.branchLevels = levels;
  p.branches = 5;
  p.twigs = 8;
  p.branchAngleDeg = 40.0f;
  p.taper = 0.3f;
  p.leafSizeM = 0.5f;
  p.leavesPerTwig = levels == 3 ? 6 : 12;
  return p;
}

// config/species.json's tree species, as the program builds them.
TreeParams catalogTree(TreeForm form) {
  for (const vegetation::Species& s : defaultSpeciesCatalog().species)
    if (isTree(s) && s.tree.form == form) return s.tree;
  ADD_FAILURE() << "the default catalog has no tree of that form";
  return {};
}

std::vector<Species> species() {
  return {{"catalog conifer", catalogTree(TreeForm::Conifer), 15.0f, 5.0f},
          {"catalog broadleaf", catalogTree(TreeForm::Broadleaf), 10.0f, 8.0f},
          {"conifer, 2 levels", conifer(2), 18.0f, 6.0f},
          {"conifer, 3 levels", conifer(3), 24.0f, 7.0f},
          {"broadleaf, 2 levels", broadleaf(2), 14.0f, 10.0f},
          {"broadleaf, 3 levels", broadleaf(3), 12.0f, 9.0f}};
}

vec3 load(const float (&a)[3]) { return {a[0], a[1], a[2]}; }

size_t triangles(const TreeMesh& mesh) { return mesh.indices.size() / 3; }

struct SideView {
  size_t cells = 0;   // cells some triangle covers
  size_t layers = 0;  // card (and bark) layers over all cells: depth complexity × cells
};

// Cells of a 64 × 64 grid over [lo, hi] (x: the horizontal axis `axis`, y: height) whose
// centres some triangle of the mesh covers, seen from the side, and how many triangles cover
// them (a card's two triangles partition it: each card counts once).
// The cells of a 64 × 64 side view that triangles [first, end) of the index list cover, and how
// many times. By default bark and cards (the crown's core is drawn before them, opaque: its own test).
struct Cells {
  std::vector<uint32_t> covered;
};
Cells sideCells(const TreeMesh& mesh, int axis, float lo, float hi, float top, size_t first, size_t end) {
  constexpr int kGrid = 64;
  std::vector<uint32_t> covered(kGrid * kGrid, 0);
  const float cellW = (hi - lo) / kGrid, cellH = top / kGrid;
  for (size_t i = first; i + 2 < end; i += 3) {
    float px[3], py[3];
    for (int k = 0; k < 3; ++k) {
      const TreeVertex& v = mesh.vertices[mesh.indices[i + static_cast<size_t>(k)]];
      px[k] = (v.position[axis] - lo) / cellW - 0.5f;
      py[k] = v.position[2] / cellH - 0.5f;
    }
    const float area = (px[1] - px[0]) * (py[2] - py[0]) - (px[2] - px[0]) * (py[1] - py[0]);
    if (std::abs(area) < 1e-9f) continue;
    const int x0 = std::max(0, static_cast<int>(std::ceil(std::min({px[0], px[1], px[2]}))));
    const int x1 = std::min(kGrid - 1, static_cast<int>(std::floor(std::max({px[0], px[1], px[2]}))));
    const int y0 = std::max(0, static_cast<int>(std::ceil(std::min({py[0], py[1], py[2]}))));
    const int y1 = std::min(kGrid - 1, static_cast<int>(std::floor(std::max({py[0], py[1], py[2]}))));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        bool inside = true;
        for (int k = 0; k < 3 && inside; ++k) {
          const int n = (k + 1) % 3;
          const float edge =
              (px[n] - px[k]) * (static_cast<float>(y) - py[k]) - (py[n] - py[k]) * (static_cast<float>(x) - px[k]);
          inside = edge * area >= 0.0f;
        }
        if (inside) ++covered[static_cast<size_t>(y * kGrid + x)];
      }
    }
  }
  return {std::move(covered)};
}

SideView sideView(const TreeMesh& mesh, int axis, float lo, float hi, float top) {
  SideView view;
  for (uint32_t n : sideCells(mesh, axis, lo, hi, top, 0, mesh.coreFirstIndex).covered)
    view.cells += n > 0 ? 1 : 0, view.layers += n;
  return view;
}

size_t silhouetteCells(const TreeMesh& mesh, int axis, float lo, float hi, float top) {
  return sideView(mesh, axis, lo, hi, top).cells;
}

TEST(TreeModel, DeterministicPerSeed) {
  for (const Species& sp : species()) {
    const TreeModel a = buildTreeModel(sp.params, sp.heightM, sp.crownM, 17);
    const TreeModel b = buildTreeModel(sp.params, sp.heightM, sp.crownM, 17);
    const TreeModel c = buildTreeModel(sp.params, sp.heightM, sp.crownM, 18);
    for (int lod = 0; lod < 2; ++lod) {
      ASSERT_EQ(a.lod[lod].vertices.size(), b.lod[lod].vertices.size()) << sp.name;
      EXPECT_EQ(std::memcmp(a.lod[lod].vertices.data(), b.lod[lod].vertices.data(),
                            a.lod[lod].vertices.size() * sizeof(TreeVertex)),
                0)
          << sp.name;
      EXPECT_EQ(a.lod[lod].indices, b.lod[lod].indices) << sp.name;
    }
    ASSERT_EQ(a.branches.size(), b.branches.size());
    EXPECT_EQ(std::memcmp(a.branches.data(), b.branches.data(), a.branches.size() * sizeof(TreeBranch)), 0);
    const bool same = a.lod[0].vertices.size() == c.lod[0].vertices.size() &&
                      std::memcmp(a.lod[0].vertices.data(), c.lod[0].vertices.data(),
                                  a.lod[0].vertices.size() * sizeof(TreeVertex)) == 0;
    EXPECT_FALSE(same) << sp.name;
  }
}

TEST(TreeModel, BranchHierarchyIsConsistent) {
  for (const Species& sp : species()) {
    for (uint32_t seed : {1u, 2u, 99u}) {
      const TreeModel m = buildTreeModel(sp.params, sp.heightM, sp.crownM, seed);
      std::set<uint32_t> levels;
      ASSERT_FALSE(m.branches.empty());
      EXPECT_EQ(m.branches[0].parent, -1);
      EXPECT_EQ(m.branches[0].level, 0u);
      const BeamFit fit = fitTaperedBeamFreeTip(sp.params.taper);
      for (size_t i = 0; i < m.branches.size(); ++i) {
        const TreeBranch& b = m.branches[i];
        levels.insert(b.level);
        const vec3 t = load(b.t), r = load(b.r), s = load(b.s);
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::length(r), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(t, r), 0.0f, 1e-5f);
        EXPECT_LT(glm::length(s - glm::cross(t, r)), 1e-5f);
        EXPECT_GT(b.length, 0.0f);
        EXPECT_NEAR(b.c2 + b.c4, 1.0f, 0.02f);  // the free-tip fit: the tip within 2 %
        EXPECT_EQ(b.c2, fit.c2);
        EXPECT_NEAR(b.frequencyHz, 2.55f * std::pow(b.length, -0.59f), 1e-5f * b.frequencyHz);
        EXPECT_GT(b.compliance, 0.0f);
        EXPECT_LE(b.compliance, b.level == 0 ? 0.02f : 0.5f);
        if (i == 0) continue;
        ASSERT_GE(b.parent, 0);
        ASSERT_LT(static_cast<size_t>(b.parent), i);
        const TreeBranch& parent = m.branches[static_cast<size_t>(b.parent)];
        EXPECT_EQ(b.level, parent.level + 1);
        EXPECT_GE(b.parentAlong, 0.0f);
        EXPECT_LE(b.parentAlong, 1.0f);
        const vec3 onAxis = load(parent.origin) + load(parent.t) * (b.parentAlong * parent.length);
        EXPECT_LT(glm::length(load(b.origin) - onAxis), 1e-3f) << sp.name << " branch " << i;
      }
      EXPECT_EQ(levels.size(), 1 + sp.params.branchLevels) << sp.name;
      EXPECT_EQ(*levels.rbegin(), sp.params.branchLevels) << sp.name;
    }
  }
}

TEST(TreeModel, MeshIsInsideTheTreeAndWellFormed) {
  for (const Species& sp : species()) {
    for (uint32_t seed : {3u, 4u, 5u, 6u}) {
      const TreeModel m = buildTreeModel(sp.params, sp.heightM, sp.crownM, seed);
      EXPECT_EQ(m.modelHeightM, sp.heightM);
      float radius = 0.0f;
      for (int lod = 0; lod < 2; ++lod) {
        const TreeMesh& mesh = m.lod[lod];
        ASSERT_EQ(mesh.indices.size() % 3, 0u);
        for (uint32_t index : mesh.indices) ASSERT_LT(index, mesh.vertices.size());
        size_t cards = 0;
        for (const TreeVertex& v : mesh.vertices) {
          ASSERT_LT(v.branch, m.branches.size());
          EXPECT_GE(v.along, 0.0f);
          EXPECT_LE(v.along, 1.0f);
          EXPECT_NEAR(glm::length(load(v.normal)), 1.0f, 1e-3f);
          EXPECT_LE(v.position[2], 1.05f * sp.heightM) << sp.name;
          EXPECT_GE(v.position[2], -0.05f * sp.heightM) << sp.name;
          radius = std::max(radius, std::hypot(v.position[0], v.position[1]));
          ASSERT_LE(v.kind, 2u);
          if (v.kind == 0) {
            EXPECT_EQ(v.flutter, 0.0f);
          }
          if (v.kind == 1) {
            ++cards;
            EXPECT_EQ(v.flutter, v.uv[1]);
            EXPECT_TRUE(v.uv[0] >= 0.0f && v.uv[0] <= 1.0f && v.uv[1] >= 0.0f && v.uv[1] <= 1.0f);
            if (lod == 1) {
              EXPECT_EQ(m.branches[v.branch].level, 1u);
            }
          }
        }
        EXPECT_GT(cards, 0u);
      }
      EXPECT_FLOAT_EQ(m.crownRadiusM, radius);
      EXPECT_LE(m.crownRadiusM, 0.5f * sp.crownM * 1.15f) << sp.name;
      EXPECT_GE(m.crownRadiusM, 0.5f * sp.crownM * 0.7f) << sp.name;
    }
  }
}

// Reduced: at most a quarter of Full's triangles, the same side view within 20 % (64 × 64 cells
// over the tree's bounding box, looking along y and along x).
TEST(TreeModel, ReducedKeepsTheSilhouetteWithAQuarterOfTheTriangles) {
  for (const Species& sp : species()) {
    double worst = 0.0;
    size_t fullTriangles = 0, reducedTriangles = 0;
    for (uint32_t seed : {7u, 8u, 9u}) {
      const TreeModel m = buildTreeModel(sp.params, sp.heightM, sp.crownM, seed);
      fullTriangles = std::max(fullTriangles, triangles(m.lod[0]));
      reducedTriangles = std::max(reducedTriangles, triangles(m.lod[1]));
      // Bark and cards (the core is the same small solid in both).
      EXPECT_LE(4 * m.lod[1].coreFirstIndex, m.lod[0].coreFirstIndex) << sp.name;
      EXPECT_LE(triangles(m.lod[0]), 12500u) << sp.name;
      for (int axis : {0, 1}) {
        const float reach = 1.2f * m.crownRadiusM, top = 1.05f * sp.heightM;
        const auto full = static_cast<double>(silhouetteCells(m.lod[0], axis, -reach, reach, top));
        const auto reduced = static_cast<double>(silhouetteCells(m.lod[1], axis, -reach, reach, top));
        worst = std::max(worst, std::abs(reduced - full) / full);
        EXPECT_LT(std::abs(reduced - full), 0.2 * full) << sp.name << " seed " << seed << " axis " << axis;
      }
    }
    std::printf("%s: Full %zu triangles, Reduced %zu, silhouette differs by %.1f %% at most\n", sp.name, fullTriangles,
                reducedTriangles, 100.0 * worst);
  }
}

// Every layer of cards costs its pixels, hidden or not (alpha-tested cards are shaded before the
// depth test can drop them): the catalog's crowns, seen from the side, stay within a few layers of
// cards — 30 (conifer) and 40 (broadleaf) made the H200 spend 40 ms a frame in the Kolob forest —
// while still filling their side view (the cells inside the crown's outline that some card covers).
TEST(TreeModel, CatalogCrownsStayWithinAFewLayersOfCards) {
  for (const Species& sp : species()) {
    if (std::string(sp.name).rfind("catalog", 0) != 0) continue;
    for (uint32_t seed : {7u, 8u, 9u}) {
      const TreeModel m = buildTreeModel(sp.params, sp.heightM, sp.crownM, seed);
      const float reach = 1.2f * m.crownRadiusM, top = 1.05f * sp.heightM;
      for (int lod : {0, 1}) {
        const SideView v = sideView(m.lod[static_cast<size_t>(lod)], 0, -reach, reach, top);
        const double layers = double(v.layers) / double(v.cells);
        std::printf("%s, seed %u, %s: %zu triangles, %.1f layers over %zu cells\n", sp.name, seed,
                    lod == 0 ? "full" : "reduced", triangles(m.lod[static_cast<size_t>(lod)]), layers, v.cells);
        EXPECT_LE(layers, lod == 0 ? 10.0 : 8.0) << sp.name << " seed " << seed;
        EXPECT_GE(layers, 2.5) << sp.name << " seed " << seed;  // still a crown, not a few cards
      }
    }
  }
}

// The crown's opaque core (tree_core.h): a closed solid (every edge shared by two triangles that
// run along it in opposite directions), the last triangles of each level of detail, inside the
// crown — its side view within the cards' and filling much of it, so what shows through the gaps
// between cards is the core and not the sky. The catalog's crowns: a sparse crown of a few whorls
// (the default parameters' test conifers) shows its core between the whorls, a weakness the
// catalog's dense crowns do not have (render/README.md "Trees").
TEST(TreeModel, TheCrownCoreIsAClosedSolidInsideTheCards) {
  for (const Species& sp : species()) {
    if (std::string(sp.name).rfind("catalog", 0) != 0) continue;
    const TreeModel m = buildTreeModel(sp.params, sp.heightM, sp.crownM, 7);
    const float reach = 1.2f * m.crownRadiusM, top = 1.05f * sp.heightM;
    for (const TreeMesh& mesh : m.lod) {
      ASSERT_LT(mesh.coreFirstIndex, mesh.indices.size()) << sp.name;
      std::map<std::pair<uint32_t, uint32_t>, int> edges;
      for (size_t i = mesh.coreFirstIndex; i < mesh.indices.size(); i += 3)
        for (int k = 0; k < 3; ++k) {
          const uint32_t a = mesh.indices[i + size_t(k)], b = mesh.indices[i + size_t((k + 1) % 3)];
          ASSERT_EQ(mesh.vertices[a].kind, 2u);
          edges[{a, b}] += 1;
        }
      for (const auto& [e, n] : edges) {
        EXPECT_EQ(n, 1) << sp.name;
        EXPECT_EQ(edges.count({e.second, e.first}), 1u) << sp.name << ": an open edge";
      }
      for (size_t i = 0; i < mesh.coreFirstIndex; ++i) ASSERT_NE(mesh.vertices[mesh.indices[i]].kind, 2u);
      for (int axis : {0, 1}) {
        const Cells cards = sideCells(mesh, axis, -reach, reach, top, 0, mesh.coreFirstIndex);
        const Cells core = sideCells(mesh, axis, -reach, reach, top, mesh.coreFirstIndex, mesh.indices.size());
        // Inside the crown's outline: each row of cells between the cards' leftmost and rightmost
        // (the gaps between cards are where the core is meant to show).
        constexpr size_t kGrid = 64;
        size_t coreCells = 0, inside = 0, cardCells = 0;
        for (size_t y = 0; y < kGrid; ++y) {
          size_t lo = kGrid, hi = 0;
          for (size_t x = 0; x < kGrid; ++x)
            if (cards.covered[y * kGrid + x] > 0) lo = std::min(lo, x), hi = x, ++cardCells;
          for (size_t x = 0; x < kGrid; ++x) {
            if (core.covered[y * kGrid + x] == 0) continue;
            ++coreCells;
            inside += x >= lo && x <= hi ? 1 : 0;
          }
        }
        std::printf("%s: the core covers %zu cells of the side view, %zu inside the outline; the cards %zu\n", sp.name,
                    coreCells, inside, cardCells);
        // A conifer's cards are the trapezoids their needles cover (tree_model.cpp kConiferTipWidth),
        // so this outline is what shows; against it the cores of the quad-card models sat 95.3–97.5 %
        // inside (measured when the cards were trimmed, the cores made from the quads), as do these.
        EXPECT_GE(inside, coreCells * 95 / 100) << sp.name << ": the core shows outside the crown";
        EXPECT_GE(coreCells * 10, cardCells * 3) << sp.name << ": the core fills too little of the crown";
        EXPECT_LE(coreCells, cardCells) << sp.name;
      }
    }
  }
}

TEST(TreeModel, BuildsInMilliseconds) {
  for (const Species& sp : species()) {
    constexpr int kModels = 20;
    const auto start = std::chrono::steady_clock::now();
    size_t vertices = 0;
    for (uint32_t seed = 0; seed < kModels; ++seed)
      vertices += buildTreeModel(sp.params, sp.heightM, sp.crownM, seed).lod[0].vertices.size();
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / kModels;
    std::printf("%s: %.2f ms per model (%zu Full vertices on average)\n", sp.name, ms, vertices / kModels);
    // A guard against a build gone quadratic, not a timing claim: about 4 ms on a quiet 2-vCPU
    // machine, up to 13 while the whole suite runs beside it.
    EXPECT_LT(ms, 100.0) << sp.name;
  }
}

}  // namespace
}  // namespace vegstream::vegetation
