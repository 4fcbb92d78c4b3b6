// ROAM output traversal: drawn leaves per piece and seed triangles (roam_tessellator.h). Seed
// 001_3eca9f2c7752e4fb.txt §3.1 (what to seed: fixed level, frustum, horizon — back faces too,
// unlike the seed;
// eye-space tricks A and B) and §2.1 (eq. 1, eq. 2).

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/stopwatch.h"
#include "terrain/roam_tessellator.h"
#include "terrain/roam_walk.h"

namespace vegstream::terrain {

void RoamTessellator::output(const EyeView& view, const PieceSet& pieces, double timeS,
                             std::vector<TerrainMesh>& meshes, std::vector<SeedTriangle>& seeds) {
  Stopwatch watch;
  ++outputFrame_;
  stamps_.resize(mesh_.vertexCapacity());
  releaseChunks();
  meshes.resize(pieces.tiles().size() + 1);
  for (size_t i = 0; i < meshes.size(); ++i) {
    TerrainMesh& m = meshes[i];
    m.clear();
    if (i < pieces.tiles().size()) {
      const geo::TileId& t = pieces.tiles()[i];
      const glm::dvec2 c = geo::tileXYToLonLat({t.x + 0.5, t.y + 0.5}, t.z);
      m.origin = frame_.toLocal({c.y, c.x, mesh_.options().fillHeightM});
    } else {
      m.origin = view.cameraEnu;
    }
  }
  seeds.clear();
  // Changes from here on are after every chunk this output builds.
  chunkEpoch_ = mesh_.closeDrawnEpoch();
  const Frustum frustum(view);
  Walk w;
  w.view = &view;
  w.frustum = &frustum;
  w.pieces = &pieces;
  w.timeS = timeS;
  w.meshes = &meshes;
  w.seeds = &seeds;
  w.untextured = static_cast<int>(pieces.tiles().size());
  figures_.drawnTriangles = figures_.constrainedLeaves = figures_.morphingVertices = 0;
  figures_.seedTriangles = figures_.seedInterpolated = 0;
  figures_.chunksReused = figures_.chunksBuilt = figures_.chunksMoved = figures_.leavesEmitted = 0;
  figures_.seedPlants = 0.0;
  for (uint32_t r : mesh_.roots()) {
    glm::dvec3 eye[3];
    eyeOf(view, r, eye);
    visitOutput(w, r, eye, Cull::Partial, kEveryPlane, InPiece::None, -1, true);
  }
  prepareChunks(w);
  appendChunkDraws(w);
  figures_.leavesEmitted += w.emitted.leaves;
  figures_.morphingVertices += w.emitted.morphingVertices;
  figures_.chunksMoved += w.emitted.chunksMoved;
  figures_.seedTriangles = seeds.size();
  mesh_.markShown();
  figures_.outputMs = watch.elapsedMs();
}

void RoamTessellator::visitOutput(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes, InPiece ps,
                                  int piece, bool seeds) {
  // Eye coordinates are needed while the culling or the seeds are undecided, and only then.
  assert(eye != nullptr || (cull == Cull::Inside && !seeds));
  const RoamNode& n = mesh_.node(t);
  mesh_.prefetchChildren(t);
  const int level = n.path.level;
  const double e = n.cullThickness();
  if (cull != Cull::Inside) {
    cull = cullWedgie(*w.frustum, eye[0], eye[1], eye[2], e, e + options_.canopyM, planes);
    if (cull == Cull::Outside) return;
  }
  if (level == 0 || (ps == InPiece::Above && level % 2 == 0)) {
    const geo::TileId square = mesh_.grid().square(mesh_.corners(t), level);
    const int exact = w.pieces->exactly(square);
    if (exact >= 0) {
      ps = InPiece::In;
      piece = exact;
    } else {
      ps = w.pieces->isAbove(square) ? InPiece::Above : InPiece::None;
    }
  }
  if (ps == InPiece::None) return;  // outside every piece: the tile selection found it invisible

  if (seeds && level <= seedLevel_) {
    if (sphereDistance(*w.view, t, eye, e) > seeds_.horizonM) {
      seeds = false;
    } else if (level == seedLevel_ || n.isLeaf()) {
      glm::dvec3 world[3];
      bool data = true;
      for (int i = 0; i < 3; ++i) {
        const RoamVertex& v = mesh_.vertex(n.v[i]);
        data = data && v.heightM == v.heightM;
        world[i] = v.position(v.heightM);
      }
      if (data) {
        const int seedPiece = ps == InPiece::In ? piece : -1;
        if (level == seedLevel_)
          emitSeed(w, n.path, world, eye, false, seedPiece);
        else
          refineSeeds(w, n.path, world, eye, e, seedPiece);
      }
      seeds = false;
    }
  }
  if (options_.cacheChunks && !seeds && ps == InPiece::In && n.leafCount <= options_.chunkMaxLeaves) {
    drawChunk(w, t, piece, cull == Cull::Inside ? PlaneMask{0} : planes);
    return;
  }
  if (n.isLeaf()) {
    if (ps == InPiece::Above) ++figures_.constrainedLeaves;
    const bool textured = ps == InPiece::In;
    TerrainMesh& m = (*w.meshes)[size_t(textured ? piece : w.untextured)];
    if (emitLeaf(w.timeS, t,
                 {&m.vertices, &m.indices, m.origin, textured ? &w.pieces->tiles()[size_t(piece)] : nullptr,
                  static_cast<uint32_t>(textured ? piece : w.untextured), nullptr, &w.emitted, nullptr}))
      ++figures_.drawnTriangles;
    return;
  }
  const uint32_t c = n.child;
  if (cull == Cull::Inside && !seeds) {
    visitOutput(w, c, nullptr, cull, 0, ps, piece, false);
    visitOutput(w, c + 1, nullptr, cull, 0, ps, piece, false);
    return;
  }
  const glm::dvec3 m = eyeOfVertex(*w.view, n.mid);  // the only vertex transformed here (§3.1 A)
  const glm::dvec3 e0[3] = {m, eye[0], eye[1]}, e1[3] = {m, eye[2], eye[0]};
  visitOutput(w, c, e0, cull, planes, ps, piece, seeds);
  visitOutput(w, c + 1, e1, cull, planes, ps, piece, seeds);
}

bool RoamTessellator::emitLeaf(double timeS, uint32_t t, const LeafSink& sink) {
  assert((sink.chunk == nullptr) == (sink.chunkVertices == nullptr) && "a chunk brings its vertex map");
  const RoamNode& n = mesh_.node(t);
  ++sink.counts->leaves;
  for (uint32_t v : n.v)
    if (!(mesh_.vertex(v).heightM == mesh_.vertex(v).heightM)) return false;  // nodata: a hole, never a drop to 0
  // 2^(z − gridZoom), exactly (a piece's zoom is below the grid's): the tile's uv per grid step.
  assert(!sink.tile || sink.tile->z < mesh_.grid().gridZoom());
  const double uvScale =
      sink.tile ? 1.0 / static_cast<double>(uint64_t{1} << (mesh_.grid().gridZoom() - sink.tile->z)) : 0.0;
  const double fade = mesh_.options().fadeS;
  for (uint32_t v : n.v) {
    uint32_t* known = nullptr;  // the chunk's entry for v
    if (sink.chunkVertices) {
      known = &sink.chunkVertices->at(v);
      if (*known != kNoNode) {
        sink.indices->push_back(*known);
        continue;
      }
    } else if (const Stamp& st = stamps_[v]; st.frame == outputFrame_ && st.piece == sink.stamp) {
      sink.indices->push_back(st.index);
      continue;
    }
    const RoamVertex& x = mesh_.vertex(v);
    const double h = x.drawnHeight(timeS, fade);
    if (h != x.heightM) ++sink.counts->morphingVertices;
    TerrainVertex out;
    out.position = glm::vec3(x.position(h) - sink.origin);
    out.normal = x.normal;
    out.heightMsl = static_cast<float>(h);
    if (sink.tile)
      out.uv = glm::vec2(double(x.grid.x) * uvScale - sink.tile->x, double(x.grid.y) * uvScale - sink.tile->y);
    const auto index = static_cast<uint32_t>(sink.vertices->size());
    if (known)
      *known = index;
    else
      stamps_[v] = {outputFrame_, sink.stamp, index};
    if (sink.chunk) {
      if (!x.morphDone(timeS, fade)) sink.chunk->morphing.emplace_back(index, x);
      sink.chunk->at.push_back(x.at);
    }
    sink.indices->push_back(index);
    sink.vertices->push_back(out);
  }
  if (sink.chunk) sink.chunk->thickness.push_back(n.cullThickness());
  return true;
}

void RoamTessellator::emitSeed(Walk& w, const TriPath& path, const glm::dvec3* world, const glm::dvec3* eye,
                               bool interpolated, int piece) {
  // The seeding horizon is measured to the nearest vertex (§3.1).
  const double nearest = std::min({glm::length(eye[0]), glm::length(eye[1]), glm::length(eye[2])});
  if (nearest > seeds_.horizonM) return;
  // Back faces are seeded too (unlike §3.1): plants stand up from ground that faces away — past
  // a crest their tops show above it — and dropping a triangle's plants the moment the camera
  // crosses its plane made them all pop at once (issue 18). The terrain's depth hides the rest,
  // and the Hi-Z occlusion test keeps them from being classified.
  SeedTriangle s;
  s.path = path;
  const std::array<glm::dvec3, 3> e{eye[0], eye[1], eye[2]};
  const double lod = seeds_.rule == PlantCountRule::ScreenArea ? plantCountScreen(*w.view, e, seeds_, &s.nearPlane)
                                                                 : plantCountWorld(*w.view, e, seeds_);
  for (int i = 0; i < 3; ++i) {
    s.world[size_t(i)] = world[i];
    s.fromCamera[size_t(i)] = glm::vec3(world[i] - w.view->cameraEnu);
  }
  s.interpolated = interpolated;
  s.corners = mesh_.grid().corners(path);
  s.piece = piece;
  const double area = groundArea(s.world);
  s.lodCount = static_cast<float>(lod);
  s.areaM2 = static_cast<float>(area);
  s.nearestM = static_cast<float>(nearest);
  s.plantCount = static_cast<float>(groundPlantCount(lod, area, nearest, seeds_));
  figures_.seedPlants += s.plantCount;
  if (interpolated) ++figures_.seedInterpolated;
  w.seeds->push_back(s);
}

void RoamTessellator::refineSeeds(Walk& w, const TriPath& path, const glm::dvec3* world, const glm::dvec3* eye,
                                  double thickness, int piece) {
  // Below a leaf coarser than the seed level: midpoint splits without the heightmap, world and
  // eye coordinates interpolated (rotations are linear: §3.1 B).
  if (cullWedgie(*w.frustum, eye[0], eye[1], eye[2], thickness, thickness + options_.canopyM) == Cull::Outside) return;
  const glm::dvec3 c = 0.5 * (eye[1] + eye[2]);
  const double radius = std::max(glm::length(eye[0] - c), glm::length(eye[1] - c));
  if (glm::length(c) - radius - thickness > seeds_.horizonM) return;
  if (path.level == seedLevel_) {
    emitSeed(w, path, world, eye, true, piece);
    return;
  }
  const glm::dvec3 mw = 0.5 * (world[1] + world[2]), me = 0.5 * (eye[1] + eye[2]);
  const glm::dvec3 w0[3] = {mw, world[0], world[1]}, w1[3] = {mw, world[2], world[0]};
  const glm::dvec3 e0[3] = {me, eye[0], eye[1]}, e1[3] = {me, eye[2], eye[0]};
  refineSeeds(w, childPath(path, 0), w0, e0, thickness, piece);
  refineSeeds(w, childPath(path, 1), w1, e1, thickness, piece);
}

}  // namespace vegstream::terrain
