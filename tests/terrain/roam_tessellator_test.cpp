// ROAM updates over the Zion heights: the on-screen error bound or the budget, culling with the
// canopy, frame-to-frame coherence, and the constraint that drawn leaves fit one piece.

#include <cmath>

#include <gtest/gtest.h>

#include "terrain/roam_tessellator.h"
#include "tests/terrain/roam_fixture.h"

namespace vegstream::terrain {
namespace {

using test::converge;
using test::zionResident;

TEST(RoamTessellator, EveryVisibleLeafMeetsTheBoundOrTheBudgetIsReported) {
  auto& z = zionResident();
  const PieceSet pieces = z.finestPieces();
  RoamOptions o;
  o.maxErrorPx = 2.0;
  auto r = z.tessellator(o);
  const EyeView view = z.camera(37.30, -113.05, 300.0, 45.0, -12.0);
  ASSERT_LT(converge(*r, view, pieces), 40);
  ASSERT_FALSE(r->figures().budgetLimited);
  uint64_t visible = 0;
  double worst = 0.0;
  for (uint32_t t : r->mesh().leaves()) {
    glm::dvec3 eye[3];
    const RoamNode& n = r->mesh().node(t);
    for (int i = 0; i < 3; ++i) {
      const RoamVertex& v = r->mesh().vertex(n.v[i]);
      eye[i] = view.toEye(v.position(v.geometryHeight(r->mesh().options().fillHeightM)));
    }
    const double e = std::max(0.0f, n.thickness);
    if (cullWedgie(view, eye[0], eye[1], eye[2], e, e) == Cull::Outside) continue;
    ++visible;
    const double px = r->errorPx(view, t);
    worst = std::max(worst, px);
    ASSERT_LE(px, o.maxErrorPx + 1e-6) << "leaf at level " << int(n.path.level);
  }
  EXPECT_GT(visible, 1000u);
  RecordProperty("visible_leaves", std::to_string(visible));
  RecordProperty("worst_error_px", std::to_string(worst));

  // The same view with a budget far below what the bound needs: the budget holds and says so.
  RoamOptions tight = o;
  tight.maxTriangles = visible / 4;
  auto b = z.tessellator(tight);
  converge(*b, view, pieces);
  b->update(view, pieces, 0.0);
  EXPECT_TRUE(b->figures().budgetLimited);
  EXPECT_LE(b->mesh().leafCount(), tight.maxTriangles + 4);
  EXPECT_EQ(b->mesh().conformityViolations(), 0u);
}

TEST(RoamTessellator, FrameToFrameCoherentAndWorkBounded) {
  auto& z = zionResident();
  const PieceSet pieces = z.finestPieces();
  RoamOptions o;
  o.maxOpsPerFrame = 500;
  auto r = z.tessellator(o);
  const EyeView a = z.camera(37.30, -113.05, 300.0, 45.0, -12.0);
  r->update(a, pieces, 0.0);
  EXPECT_TRUE(r->figures().workLimited);
  EXPECT_LE(r->figures().splits + r->figures().merges, 500u);
  converge(*r, a, pieces, 400);
  const uint64_t leaves = r->mesh().leafCount();
  // A small move changes a small part of the mesh.
  const EyeView b = z.camera(37.3003, -113.0497, 300.0, 46.0, -12.0);
  r->update(b, pieces, 0.0);
  EXPECT_LT(r->figures().splits + r->figures().merges, leaves / 10);
  EXPECT_EQ(r->mesh().conformityViolations(), 0u);
}

TEST(RoamTessellator, EveryLeafInTheViewIsDrawnInsideOnePiece) {
  auto& z = zionResident();
  const PieceSet pieces = z.finestPieces();
  auto r = z.tessellator();
  const EyeView view = z.camera(37.25, -113.10, 500.0, 30.0, -20.0, 320.0, 180.0);
  converge(*r, view, pieces);
  std::vector<TerrainMesh> meshes;
  std::vector<SeedTriangle> seeds;
  r->output(view, pieces, 0.0, meshes, seeds);
  ASSERT_EQ(meshes.size(), pieces.tiles().size() + 1);
  EXPECT_EQ(meshes.back().triangleCount(), 0u) << "every drawn leaf fits one piece once converged";
  uint64_t triangles = 0, inChunks = 0;
  for (size_t p = 0; p < pieces.tiles().size(); ++p) {
    const TerrainMesh& m = meshes[p];
    forEachTriangle(m, [&](const TerrainVertex& a, const TerrainVertex& b, const TerrainVertex& c) {
      for (const TerrainVertex* v : {&a, &b, &c}) {  // uv inside the piece's tile
        EXPECT_GE(v->uv.x, -1e-4f);
        EXPECT_LE(v->uv.x, 1.0001f);
        EXPECT_GE(v->uv.y, -1e-4f);
        EXPECT_LE(v->uv.y, 1.0001f);
      }
      ++triangles;
    });
    for (const TerrainChunkDraw& d : m.chunks) inChunks += d.count / 3;
  }
  EXPECT_GT(inChunks, 0u) << "the cached chunks are drawn by reference";
  EXPECT_GT(triangles, 500u);
  EXPECT_EQ(triangles, r->figures().drawnTriangles);
  // The hierarchical culling emits every leaf whose own wedgie (thickness + canopy) is not
  // entirely outside the view, none lost; of those outside, only ones in a drawn chunk that
  // straddles the edge of the view (drawn whole, roam_chunks.h).
  uint64_t expected = 0, outside = 0, outsideDrawable = 0;
  const double fill = r->mesh().options().fillHeightM;
  for (uint32_t t : r->mesh().leaves()) {
    const RoamNode& n = r->mesh().node(t);
    glm::dvec3 eye[3];
    bool data = true;
    for (int k = 0; k < 3; ++k) {
      const RoamVertex& v = r->mesh().vertex(n.v[k]);
      data = data && v.heightM == v.heightM;
      eye[k] = view.toEye(v.position(v.geometryHeight(fill)));
    }
    const double e = std::max(0.0f, n.thickness);
    const bool in = cullWedgie(view, eye[0], eye[1], eye[2], e, e + r->options().canopyM) != Cull::Outside;
    const bool drawable = data && pieces.pieceOf(z.grid().square(r->mesh().corners(t), n.path.level)) >= 0;
    if (!in) ++outside;
    if (in && drawable) ++expected;
    if (!in && drawable) ++outsideDrawable;
  }
  EXPECT_GE(r->figures().drawnTriangles, expected);
  EXPECT_LE(r->figures().drawnTriangles, expected + outsideDrawable);
  // The chunks along the edge add a rim of at most a chunk's width (here 7 %, a 320 × 180 view).
  EXPECT_LT(double(r->figures().drawnTriangles), 1.15 * double(expected));
  EXPECT_GT(outside, 0u) << "the view leaves some of the mesh out";
}

TEST(RoamTessellator, TheFirstDrawnMeshIsAtItsHeightsThenSplitsMorph) {
  // Before anything was drawn there is nothing to morph from: the first output draws every
  // vertex at its sampled height (a morph from the coarse interpolation drew the Kolob plateau
  // 39 m low under a camera 2 m up, and culling at the true heights cut holes in the view).
  auto& z = zionResident();
  const PieceSet pieces = z.finestPieces();
  auto r = z.tessellator({}, {}, 0.5);
  const EyeView eye = z.camera(37.457, -113.022, 2.0, 90.0, -12.0, 320.0, 180.0);
  for (int i = 0; i < 3; ++i) r->update(eye, pieces, 0.0);  // warm-up frames: all at time 0
  EXPECT_FALSE(r->mesh().shown());
  std::vector<TerrainMesh> meshes;
  std::vector<SeedTriangle> seeds;
  r->output(eye, pieces, 0.0, meshes, seeds);
  EXPECT_TRUE(r->mesh().shown());
  EXPECT_EQ(r->figures().morphingVertices, 0u);
  uint64_t vertices = 0;
  for (uint32_t v = 0; v < r->mesh().vertexCapacity(); ++v) {
    const RoamVertex& x = r->mesh().vertex(v);
    if (!(x.heightM == x.heightM)) continue;
    ++vertices;
    EXPECT_EQ(x.drawnHeight(0.0, 0.5), x.heightM);
  }
  EXPECT_GT(vertices, 1000u);
  // Once shown, a split's vertices morph (SplitsAndMergesMorphInsteadOfPopping).
  const EyeView lower = z.camera(37.457, -113.022, 0.5, 90.0, -12.0, 320.0, 180.0);
  r->update(lower, pieces, 1.0);
  if (r->figures().splits > 0) {
    r->output(lower, pieces, 1.0, meshes, seeds);
    EXPECT_GT(r->figures().morphingVertices, 0u);
  }
}

TEST(RoamTessellator, SplitsAndMergesMorphInsteadOfPopping) {
  auto& z = zionResident();
  const PieceSet pieces = z.finestPieces();
  auto r = z.tessellator({}, {}, 0.5);
  const EyeView near = z.camera(37.30, -113.05, 120.0, 45.0, -20.0, 320.0, 180.0);
  for (int i = 0; i < 40; ++i) r->update(near, pieces, 10.0 + i);  // converged, morphs long done
  r->mesh().markShown();  // drawn: from now on changes morph
  // New vertices start on the base they split (their parent's surface) and rise over fadeS.
  const EyeView closer = z.camera(37.30, -113.05, 40.0, 45.0, -20.0, 320.0, 180.0);
  r->update(closer, pieces, 100.0);
  ASSERT_GT(r->figures().splits, 0u);
  uint64_t rising = 0;
  const RoamMesh& m = r->mesh();
  for (uint32_t t : m.leaves()) {
    const RoamNode& n = m.node(t);
    const RoamVertex& apex = m.vertex(n.v[0]);
    if (apex.morphStartS != 100.0 || apex.merging || !(apex.heightM == apex.heightM)) continue;
    ++rising;
    EXPECT_NEAR(apex.drawnHeight(100.0, 0.5), apex.fromHeightM, 1e-9);
    EXPECT_NEAR(apex.drawnHeight(100.5, 0.5), apex.heightM, 1e-9);
  }
  EXPECT_GT(rising, 0u);
  // Climbing away: visible diamonds first sink to their bases, and merge only after fadeS.
  for (int i = 0; i < 40; ++i) r->update(closer, pieces, 101.0 + i);
  const EyeView far = z.camera(37.30, -113.05, 600.0, 45.0, -20.0, 320.0, 180.0);
  r->update(far, pieces, 200.0);
  const uint64_t started = r->figures().mergesStarted;
  EXPECT_GT(started, 0u);
  uint64_t sinking = 0;
  for (uint32_t v = 0; v < m.vertexCapacity(); ++v) {
    const RoamVertex& x = m.vertex(v);
    if (!x.merging) continue;
    ++sinking;
    EXPECT_EQ(x.morphStartS, 200.0);
    EXPECT_NEAR(x.drawnHeight(200.5, 0.5), x.toHeightM, 1e-9);
  }
  EXPECT_EQ(sinking, started);
  r->update(far, pieces, 200.25);  // half way: the sinking ones have not merged
  uint64_t stillSinking = 0;
  for (uint32_t v = 0; v < m.vertexCapacity(); ++v) stillSinking += m.vertex(v).merging;
  EXPECT_GE(stillSinking, started);
  r->update(far, pieces, 200.6);  // done: they merge
  EXPECT_GT(r->figures().merges, 0u);
  EXPECT_EQ(m.conformityViolations(), 0u);
}

// True when a drawn triangle contains the point (x, y) of the ENU plane.
bool drawnOver(const std::vector<TerrainMesh>& meshes, glm::dvec2 p) {
  bool over = false;
  for (const TerrainMesh& m : meshes)
    forEachTriangle(m, [&](const TerrainVertex& a, const TerrainVertex& b, const TerrainVertex& c) {
      glm::dvec2 v[3];
      const TerrainVertex* abc[3] = {&a, &b, &c};
      for (int k = 0; k < 3; ++k) v[k] = glm::dvec2(m.origin + glm::dvec3(abc[k]->position));
      auto side = [&](glm::dvec2 x, glm::dvec2 y) { return (y.x - x.x) * (p.y - x.y) - (y.y - x.y) * (p.x - x.x); };
      if (side(v[0], v[1]) >= 0 && side(v[1], v[2]) >= 0 && side(v[2], v[0]) >= 0) over = true;
    });
  return over;
}

TEST(RoamTessellator, ATriangleWhoseCanopyPokesIntoViewIsKept) {
  auto& z = zionResident();
  const PieceSet pieces = z.finestPieces();
  // 8 m over the ground looking up 40°: the bottom of the view is 10° above the horizon, so the
  // ground under the camera is out of view, but plants up to 30 m there reach past the camera.
  const EyeView view = z.camera(37.20, -113.00, 8.0, 0.0, 40.0, 320.0, 180.0);
  const glm::dvec2 under(view.cameraEnu);
  for (double canopy : {30.0, 0.0}) {
    RoamOptions o;
    o.canopyM = canopy;
    auto r = z.tessellator(o);
    converge(*r, view, pieces);
    std::vector<TerrainMesh> meshes;
    std::vector<SeedTriangle> seeds;
    r->output(view, pieces, 0.0, meshes, seeds);
    EXPECT_EQ(drawnOver(meshes, under), canopy > 0.0) << "canopy " << canopy;
  }
}

}  // namespace
}  // namespace vegstream::terrain
