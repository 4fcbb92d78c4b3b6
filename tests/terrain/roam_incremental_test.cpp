// The incremental ROAM work — deferred priority recomputation in the update and the drawn
// chunks cached by the output — against doing all of it every frame: a flight over the Zion
// heights that moves, turns and morphs must give the same mesh and draw the same triangles.

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "core/task_runner.h"
#include "terrain/roam_tessellator.h"
#include "tests/terrain/roam_fixture.h"

namespace vegstream::terrain {
namespace {

using test::zionResident;

// Frame i of a low flight that advances ~1.5 m a frame, turns and pitches.
EyeView flightView(test::ZionResident& z, int i) {
  const double s = i / 60.0;
  return z.camera(37.25 + 0.00012 * s * 60.0 / 10.0, -113.05 + 0.0001 * s * 6.0, 250.0 - 40.0 * s, 30.0 + 25.0 * s,
                  -15.0 + 3.0 * std::sin(s), 640.0, 360.0);
}

std::vector<TriPath> leafPaths(const RoamTessellator& r) {
  std::vector<TriPath> out;
  for (uint32_t t : r.mesh().leaves()) out.push_back(r.mesh().node(t).path);
  std::sort(out.begin(), out.end());
  return out;
}

// Every drawn triangle as its three vertices in the frame (origin + position), per mesh.
using Triangle = std::array<float, 10>;  // 9 coordinates and the mesh index
std::vector<Triangle> drawn(const std::vector<TerrainMesh>& meshes) {
  std::vector<Triangle> out;
  for (size_t m = 0; m < meshes.size(); ++m) {
    forEachTriangle(meshes[m], [&](const TerrainVertex& a, const TerrainVertex& b, const TerrainVertex& c) {
      Triangle t{};
      const TerrainVertex* abc[3] = {&a, &b, &c};
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j) t[size_t(3 * k + j)] = abc[k]->position[j];
      t[9] = static_cast<float>(m);
      out.push_back(t);
    });
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The chunks draw every triangle the direct output (each leaf culled on its own) draws; a chunk
// that straddles the edge of the view is drawn whole, so they may draw more: those, returned.
std::vector<Triangle> drawnBeyondTheDirectOutput(const std::vector<TerrainMesh>& direct,
                                                 const std::vector<TerrainMesh>& chunked, int frame) {
  const std::vector<Triangle> fromLeaves = drawn(direct), fromChunks = drawn(chunked);
  EXPECT_TRUE(std::includes(fromChunks.begin(), fromChunks.end(), fromLeaves.begin(), fromLeaves.end()))
      << "frame " << frame;
  std::vector<Triangle> more;
  std::set_difference(fromChunks.begin(), fromChunks.end(), fromLeaves.begin(), fromLeaves.end(),
                      std::back_inserter(more));
  return more;
}

TEST(RoamIncremental, DeferredPrioritiesMakeTheSameMeshAsComputingEveryPriority) {
  auto& z = zionResident();
  const PieceSet pieces = z.finestPieces();
  RoamOptions every;
  every.deferPriorities = false;
  auto full = z.tessellator(every, {}, 0.5);
  auto deferred = z.tessellator({}, {}, 0.5);
  uint64_t computedFull = 0, computedDeferred = 0, changed = 0;
  for (int i = 0; i < 150; ++i) {
    const EyeView view = flightView(z, i);
    full->update(view, pieces, i / 60.0);
    deferred->update(view, pieces, i / 60.0);
    computedFull += full->figures().prioritiesComputed;
    computedDeferred += deferred->figures().prioritiesComputed;
    changed += deferred->figures().splits + deferred->figures().merges;
    ASSERT_EQ(leafPaths(*full), leafPaths(*deferred)) << "frame " << i;
    ASSERT_EQ(full->figures().achievedErrorPx <= 2.0, deferred->figures().achievedErrorPx <= 2.0) << "frame " << i;
  }
  EXPECT_GT(changed, 1000u) << "the flight changes the mesh";
  EXPECT_EQ(deferred->mesh().conformityViolations(), 0u);
  // Deferral does a small part of the work (the ratio, measured: about 1/5 to 1/10 here).
  EXPECT_LT(computedDeferred * 3, computedFull);
  RecordProperty("priorities_every_frame", std::to_string(computedFull));
  RecordProperty("priorities_deferred", std::to_string(computedDeferred));
}

TEST(RoamIncremental, CachedChunksDrawEveryTriangleOfTheDirectOutput) {
  auto& z = zionResident();
  const PieceSet pieces = z.finestPieces();
  RoamOptions direct;
  direct.cacheChunks = false;
  auto a = z.tessellator(direct, {}, 0.5);
  auto b = z.tessellator({}, {}, 0.5);
  std::vector<TerrainMesh> ma, mb;
  std::vector<SeedTriangle> sa, sb;
  uint64_t reused = 0, built = 0, compactions = 0;
  for (int i = 0; i < 150; ++i) {
    const EyeView view = flightView(z, i);
    const double t = i / 60.0;
    a->update(view, pieces, t);
    b->update(view, pieces, t);
    a->output(view, pieces, t, ma, sa);
    b->output(view, pieces, t, mb, sb);
    reused += b->figures().chunksReused;
    built += b->figures().chunksBuilt;
    compactions += b->figures().compacted && i > 0 ? 1 : 0;
    const std::vector<Triangle> more = drawnBeyondTheDirectOutput(ma, mb, i);
    if (HasFailure()) return;
    ASSERT_EQ(a->figures().drawnTriangles + more.size(), b->figures().drawnTriangles) << "frame " << i;
    ASSERT_EQ(sa.size(), sb.size()) << "frame " << i;
  }
  EXPECT_GT(b->figures().drawnTriangles, 1000u);
  EXPECT_GT(reused, 10 * built) << "most chunks are appended as cached";
  // The pools were renumbered under live chunks (after the first output), and they still match.
  EXPECT_GE(compactions, 2u);
  RecordProperty("chunks_reused", std::to_string(reused));
  RecordProperty("chunks_built", std::to_string(built));
}

// Compactions whose copy runs on a worker (RoamOptions::tasks, as the app has them) give the
// same mesh, the same triangles and the same cached chunks as compactions in the update; so do
// those whose copy no worker took (a runner that never runs: the next update makes it).
TEST(RoamIncremental, CompactionsOnAWorkerGiveTheSameMeshTrianglesAndChunks) {
  auto& z = zionResident();
  const PieceSet pieces = z.finestPieces();
  ThreadPool pool(1);
  ManualTaskRunner never;
  RoamOptions onPool, onNone;
  onPool.tasks = &pool;
  onNone.tasks = &never;
  auto a = z.tessellator({}, {}, 0.5);
  auto b = z.tessellator(onPool, {}, 0.5);
  auto c = z.tessellator(onNone, {}, 0.5);
  std::vector<TerrainMesh> ma, mb, mc;
  std::vector<SeedTriangle> sa, sb, sc;
  uint64_t compactions = 0, reused = 0;
  for (int i = 0; i < 150; ++i) {
    const EyeView view = flightView(z, i);
    const double t = i / 60.0;
    a->update(view, pieces, t);
    b->update(view, pieces, t);
    c->update(view, pieces, t);
    a->output(view, pieces, t, ma, sa);
    b->output(view, pieces, t, mb, sb);
    c->output(view, pieces, t, mc, sc);
    compactions += a->figures().compacted && i > 0 ? 1 : 0;
    reused += a->figures().chunksReused;
    for (const RoamTessellator* x : {b.get(), c.get()}) {
      ASSERT_EQ(x->figures().compacted, a->figures().compacted) << "frame " << i;
      ASSERT_EQ(x->figures().chunksBuilt, a->figures().chunksBuilt) << "frame " << i;
      ASSERT_EQ(x->figures().chunksReused, a->figures().chunksReused) << "frame " << i;
      ASSERT_EQ(x->figures().drawnTriangles, a->figures().drawnTriangles) << "frame " << i;
    }
    ASSERT_EQ(drawn(ma), drawn(mb)) << "frame " << i;
    ASSERT_EQ(drawn(ma), drawn(mc)) << "frame " << i;
    ASSERT_EQ(sa.size(), sb.size()) << "frame " << i;
    ASSERT_EQ(sa.size(), sc.size()) << "frame " << i;
  }
  EXPECT_GE(compactions, 2u);
  EXPECT_GT(reused, 1000u);
  EXPECT_EQ(leafPaths(*a), leafPaths(*b));  // mesh() applies the last compaction first
  EXPECT_EQ(leafPaths(*a), leafPaths(*c));
  EXPECT_EQ(b->mesh().conformityViolations(), 0u);
  // The copies the manual runner was given were made by the updates: run now, they do nothing.
  EXPECT_GE(never.runAll(), compactions);
  EXPECT_EQ(leafPaths(*a), leafPaths(*c));
}

// Two outputs, field by field and in order (vertices, indices, chunk draws and what they draw).
void expectSameMeshes(const std::vector<TerrainMesh>& a, const std::vector<TerrainMesh>& b, int frame) {
  ASSERT_EQ(a.size(), b.size());
  auto sameVertices = [&](const std::vector<TerrainVertex>& x, const std::vector<TerrainVertex>& y) {
    ASSERT_EQ(x.size(), y.size()) << "frame " << frame;
    for (size_t i = 0; i < x.size(); ++i) {
      ASSERT_EQ(x[i].position, y[i].position) << "frame " << frame << " vertex " << i;
      ASSERT_EQ(x[i].normal, y[i].normal) << "frame " << frame << " vertex " << i;
      ASSERT_EQ(x[i].heightMsl, y[i].heightMsl) << "frame " << frame << " vertex " << i;
      ASSERT_EQ(x[i].uv, y[i].uv) << "frame " << frame << " vertex " << i;
    }
  };
  for (size_t m = 0; m < a.size(); ++m) {
    ASSERT_EQ(a[m].origin, b[m].origin);
    sameVertices(a[m].vertices, b[m].vertices);
    ASSERT_EQ(a[m].indices, b[m].indices) << "frame " << frame << " mesh " << m;
    ASSERT_EQ(a[m].chunks.size(), b[m].chunks.size()) << "frame " << frame << " mesh " << m;
    for (size_t c = 0; c < a[m].chunks.size(); ++c) {
      const TerrainChunkDraw &x = a[m].chunks[c], &y = b[m].chunks[c];
      ASSERT_EQ(x.count, y.count);
      ASSERT_EQ(x.chunk->version, y.chunk->version);
      sameVertices(x.chunk->vertices, y.chunk->vertices);
      ASSERT_EQ(x.chunk->indices, y.chunk->indices) << "frame " << frame << " mesh " << m << " chunk " << c;
    }
  }
}

// The update's priority traversal in subtrees and the output's work per chunk (building,
// moving morphs), on three workers and the
// frame thread, give what one thread gives: the same splits and merges, and the same vertices,
// indices and chunk draws in the same order.
TEST(RoamIncremental, UpdateAndOutputOnWorkersGiveTheSameMeshAndOutputInTheSameOrder) {
  auto& z = zionResident();
  const PieceSet pieces = z.finestPieces();
  ThreadPool pool(3);
  RoamOptions onPool;
  onPool.tasks = &pool;
  auto a = z.tessellator({}, {}, 0.5);
  auto b = z.tessellator(onPool, {}, 0.5);
  std::vector<TerrainMesh> ma, mb;
  std::vector<SeedTriangle> sa, sb;
  uint64_t built = 0, moved = 0, visited = 0, tasks = 0;
  for (int i = 0; i < 120; ++i) {
    const EyeView view = flightView(z, i);
    const double t = i / 60.0;
    a->update(view, pieces, t);
    b->update(view, pieces, t);
    const RoamFigures ua = a->figures(), ub = b->figures();
    ASSERT_EQ(ua.splits, ub.splits) << "frame " << i;
    ASSERT_EQ(ua.merges, ub.merges) << "frame " << i;
    ASSERT_EQ(ua.mergesStarted, ub.mergesStarted) << "frame " << i;
    ASSERT_EQ(ua.nodesVisited, ub.nodesVisited) << "frame " << i;
    ASSERT_EQ(ua.prioritiesComputed, ub.prioritiesComputed) << "frame " << i;
    ASSERT_EQ(ua.achievedErrorPx, ub.achievedErrorPx) << "frame " << i;
    visited += ua.nodesVisited;
    tasks += ub.priorityTasks;
    ASSERT_EQ(ua.priorityTasks, 0u);
    a->output(view, pieces, t, ma, sa);
    b->output(view, pieces, t, mb, sb);
    expectSameMeshes(ma, mb, i);
    if (HasFatalFailure()) return;
    const RoamFigures &fa = a->figures(), &fb = b->figures();
    ASSERT_EQ(fa.chunksBuilt, fb.chunksBuilt) << "frame " << i;
    ASSERT_EQ(fa.chunksMoved, fb.chunksMoved) << "frame " << i;
    ASSERT_EQ(fa.leavesEmitted, fb.leavesEmitted) << "frame " << i;
    ASSERT_EQ(fa.morphingVertices, fb.morphingVertices) << "frame " << i;
    ASSERT_EQ(fa.drawnTriangles, fb.drawnTriangles) << "frame " << i;
    ASSERT_EQ(sa.size(), sb.size()) << "frame " << i;
    built += fa.chunksBuilt;
    moved += fa.chunksMoved;
  }
  EXPECT_EQ(leafPaths(*a), leafPaths(*b));
  // What the comparison covered: a traversal larger than one task, chunks built and moved while
  // morphing.
  EXPECT_GT(visited / 120, 4u * 1024u);
  EXPECT_GT(tasks / 120, 8u);
  EXPECT_GT(built, 1000u);
  EXPECT_GT(moved, 100u);
}

// What a renderer that keeps chunks on the GPU does: a chunk is copied only when its id is new
// or its version changed; the rest of each mesh is taken as it is every frame.
class ChunkKeeper {
 public:
  // The meshes as the keeper sees them: the kept chunks' copies stand in for the originals.
  std::vector<TerrainMesh> view(const std::vector<TerrainMesh>& meshes) {
    std::vector<TerrainMesh> out = meshes;
    for (TerrainMesh& m : out)
      for (TerrainChunkDraw& d : m.chunks) {
        Kept& k = kept_[d.chunk->id];
        if (k.copy.id == 0 || k.copy.version != d.chunk->version) {
          // An id names one set of triangles for good: a new version only moves vertices.
          if (k.copy.id != 0) {
            EXPECT_EQ(k.copy.indices, d.chunk->indices) << "chunk " << d.chunk->id;
          }
          k.copy = *d.chunk;
          ++copied;
        } else {
          ++untouched;
        }
        d.chunk = &k.copy;
      }
    return out;
  }
  uint64_t copied = 0, untouched = 0;

 private:
  struct Kept {
    TerrainChunk copy;
  };
  std::map<uint64_t, Kept> kept_;  // std::map: the copies keep their address
};

// How far a drawn triangle (mesh-relative positions) lies outside the view: the largest, over
// the view's planes, of the distance its farthest-in corner is outside that plane (negative:
// some corner inside every plane).
double outsideTheViewM(const EyeView& view, const glm::dvec3& origin, const Triangle& t) {
  const Frustum frustum(view);
  double out = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < 5; ++k) {
    double in = -std::numeric_limits<double>::infinity();
    for (int c = 0; c < 3; ++c) {
      const glm::dvec3 p = origin + glm::dvec3(t[size_t(3 * c)], t[size_t(3 * c + 1)], t[size_t(3 * c + 2)]);
      in = std::max(in, frustum.distance(view.toEye(p), k));
    }
    out = std::max(out, -in);
  }
  return out;
}

// The chunks draw every triangle the direct output (each leaf culled on its own) draws, and
// more only where a chunk straddles the edge of the view: it is drawn whole, so the extra
// triangles are the ones the direct output culled, each wholly outside one plane of the view.
TEST(RoamIncremental, ChunksKeptByIdAndVersionDrawTheDirectOutputsTrianglesAndMoreOnlyOutsideTheView) {
  auto& z = zionResident();
  const PieceSet pieces = z.finestPieces();
  RoamOptions direct;
  direct.cacheChunks = false;
  auto a = z.tessellator(direct, {}, 0.5);
  auto b = z.tessellator({}, {}, 0.5);
  std::vector<TerrainMesh> ma, mb;
  std::vector<SeedTriangle> sa, sb;
  ChunkKeeper keeper;
  uint64_t settledExtra = 0;
  // The flight, then the camera holding still while the morphs finish: chunks stop changing.
  for (int i = 0; i < 150; ++i) {
    const EyeView view = flightView(z, std::min(i, 110));
    const double t = i / 60.0;
    a->update(view, pieces, t);
    b->update(view, pieces, t);
    a->output(view, pieces, t, ma, sa);
    b->output(view, pieces, t, mb, sb);
    for (const TerrainMesh& m : mb) {
      EXPECT_TRUE(m.vertices.empty() || !m.indices.empty());
      for (const TerrainChunkDraw& d : m.chunks) {
        ASSERT_EQ(d.count, d.chunk->indices.size()) << "a chunk is drawn whole";
        // The draw's copy of the chunk's header is the chunk's as it is now.
        ASSERT_EQ(d.id, d.chunk->id);
        ASSERT_EQ(d.version, d.chunk->version);
        ASSERT_EQ(d.vertexCount, d.chunk->vertices.size());
        ASSERT_EQ(d.boundsMin, d.chunk->boundsMin);
        ASSERT_EQ(d.boundsMax, d.chunk->boundsMax);
        // The box the renderer orders the pieces by is the one of the chunk's vertices now.
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
        growBox(d.chunk->vertices, lo, hi);
        ASSERT_FALSE(d.chunk->vertices.empty());
        ASSERT_EQ(d.chunk->boundsMin, lo) << "chunk " << d.chunk->id << ", frame " << i;
        ASSERT_EQ(d.chunk->boundsMax, hi) << "chunk " << d.chunk->id << ", frame " << i;
      }
    }
    const uint64_t copiedBefore = keeper.copied, untouchedBefore = keeper.untouched;
    const std::vector<Triangle> more = drawnBeyondTheDirectOutput(ma, keeper.view(mb), i);
    if (HasFailure()) return;
    // The culling judges a leaf by its vertices at their heights to be (RoamVertex::at), not
    // where a morph draws them now: once nothing morphs, each extra triangle is outside the view.
    if (b->figures().morphingVertices == 0) {
      for (const Triangle& tri : more)
        ASSERT_GT(outsideTheViewM(view, mb[size_t(tri[9])].origin, tri), -0.01) << "frame " << i;
      settledExtra += more.size();
    }
    ASSERT_EQ(sa.size(), sb.size()) << "frame " << i;
    if (i >= 145) {  // 0.5 s (the morphs) after the camera stopped
      EXPECT_EQ(keeper.copied, copiedBefore) << "a still camera over a settled mesh changes no chunk, frame " << i;
      EXPECT_GT(keeper.untouched, untouchedBefore);
    }
  }
  EXPECT_GT(settledExtra, 0u) << "some chunks straddle the edge of a settled view";
  // (This flight splits and morphs nearly everywhere it looks: most chunks change while it moves.)
  EXPECT_GT(keeper.untouched, 0u);
  RecordProperty("chunks_copied", std::to_string(keeper.copied));
  RecordProperty("chunks_untouched", std::to_string(keeper.untouched));
}

}  // namespace
}  // namespace vegstream::terrain
