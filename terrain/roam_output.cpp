// RoamOutput (roam_output.h): ROAM output traversal, drawn leaves per piece and seed triangles.
// Seed 001_3eca9f2c7752e4fb.txt §3.1 (what to seed: fixed level, frustum, horizon — back faces
// too, unlike the seed; eye-space tricks A and B) and §2.1 (eq. 1, eq. 2).

#include "terrain/roam_output.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include <glm/geometric.hpp>

#include "terrain/roam_error.h"

namespace vegstream::terrain {

struct RoamOutput::Walk {
  ChunkPass pass;  // view, frustum, pieces, meshes, time, counts: what the chunks need too
  std::vector<SeedTriangle>* seeds = nullptr;
  int untextured = -1;  // index of the mesh for leaves not yet inside a piece
  EmitCounts emitted;   // the direct output's
};

RoamOutput::RoamOutput(RoamMesh& mesh, const geo::LocalFrame& frame, const RoamOptions& options,
                       const SeedOptions& seeds, int seedLevel, RoamFigures& figures)
    : mesh_(mesh), frame_(frame), options_(options), seeds_(seeds), seedLevel_(seedLevel), figures_(figures),
      chunks_(mesh, options, figures) {}

void RoamOutput::resetPieces(const EyeView& view, const PieceSet& pieces, std::vector<TerrainMesh>& meshes) const {
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
}

void RoamOutput::run(const EyeView& view, const PieceSet& pieces, double timeS, std::vector<TerrainMesh>& meshes,
                     std::vector<SeedTriangle>& seeds, bool attachChunks) {
  ++outputFrame_;
  stamps_.resize(mesh_.vertexCapacity());
  chunks_.beginOutput();
  resetPieces(view, pieces, meshes);
  seeds.clear();
  const Frustum frustum(view);
  Walk w;
  w.pass = {&view, &frustum, &pieces, &meshes, timeS, &w.emitted, attachChunks};
  w.seeds = &seeds;
  w.untextured = static_cast<int>(pieces.tiles().size());
  figures_.drawnTriangles = figures_.constrainedLeaves = figures_.morphingVertices = 0;
  figures_.seedTriangles = figures_.seedInterpolated = 0;
  figures_.chunksReused = figures_.chunksBuilt = figures_.chunksMoved = figures_.leavesEmitted = 0;
  figures_.seedPlants = 0.0;
  for (uint32_t r : mesh_.roots()) {
    glm::dvec3 eye[3];
    eyeOf(mesh_, view, r, eye);
    visit(w, r, eye, Cull::Partial, kEveryPlane, InPiece::None, -1, true);
  }
  chunks_.finish(w.pass);
  figures_.leavesEmitted += w.emitted.leaves;
  figures_.morphingVertices += w.emitted.morphingVertices;
  figures_.chunksMoved += w.emitted.chunksMoved;
  figures_.seedTriangles = seeds.size();
  mesh_.markShown();
}

void RoamOutput::visit(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes, InPiece ps, int piece,
                       bool seeds) {
  // Eye coordinates are needed while the culling or the seeds are undecided, and only then.
  assert(eye != nullptr || (cull == Cull::Inside && !seeds));
  const RoamNode& n = mesh_.node(t);
  mesh_.prefetchChildren(t);
  const int level = n.path.level;
  const double e = n.cullThickness();
  if (cull != Cull::Inside) {
    cull = cullWedgie(*w.pass.frustum, eye[0], eye[1], eye[2], e, e + options_.canopyM, planes);
    if (cull == Cull::Outside) return;
  }
  if (level == 0 || (ps == InPiece::Above && level % 2 == 0)) {
    const geo::TileId square = mesh_.grid().square(mesh_.corners(t), level);
    const int exact = w.pass.pieces->exactly(square);
    if (exact >= 0) {
      ps = InPiece::In;
      piece = exact;
    } else {
      ps = w.pass.pieces->isAbove(square) ? InPiece::Above : InPiece::None;
    }
  }
  if (ps == InPiece::None) return;  // outside every piece: the tile selection found it invisible
  if (seeds && level <= seedLevel_) seeds = seedsAt(w, t, eye, e, ps, piece);
  if (options_.cacheChunks && !seeds && ps == InPiece::In && n.leafCount <= options_.chunkMaxLeaves) {
    chunks_.draw(w.pass, t, piece);
    return;
  }
  if (n.isLeaf()) {
    emitDrawnLeaf(w, t, ps, piece);
    return;
  }
  const uint32_t c = n.child;
  if (cull == Cull::Inside && !seeds) {
    visit(w, c, nullptr, cull, 0, ps, piece, false);
    visit(w, c + 1, nullptr, cull, 0, ps, piece, false);
    return;
  }
  const glm::dvec3 m = eyeOfVertex(mesh_, *w.pass.view, n.mid);  // the only vertex transformed here (§3.1 A)
  const glm::dvec3 e0[3] = {m, eye[0], eye[1]}, e1[3] = {m, eye[2], eye[0]};
  visit(w, c, e0, cull, planes, ps, piece, seeds);
  visit(w, c + 1, e1, cull, planes, ps, piece, seeds);
}

bool RoamOutput::seedsAt(Walk& w, uint32_t t, const glm::dvec3* eye, double thickness, InPiece ps, int piece) {
  const RoamNode& n = mesh_.node(t);
  const int level = n.path.level;
  if (ErrorGeometry::of(*w.pass.view, eye, thickness, n.radius).sphereDistance() > seeds_.horizonM) return false;
  if (level != seedLevel_ && !n.isLeaf()) return true;
  glm::dvec3 world[3];
  bool data = true;
  for (int i = 0; i < 3; ++i) {
    const RoamVertex& v = mesh_.vertex(n.v[i]);
    data = data && v.heightM == v.heightM;
    world[i] = v.position(v.heightM);
  }
  if (data) {
    const int seedPiece = ps == InPiece::In ? piece : -1;
    const SeedPlace at{n.path, mesh_.corners(t)};  // its vertices' grid points: just read
    assert(at.corners == mesh_.grid().corners(n.path));
    if (level == seedLevel_)
      emitSeed(w, at, world, eye, false, seedPiece);
    else
      refineSeeds(w, at, world, eye, thickness, seedPiece);
  }
  return false;
}

void RoamOutput::emitDrawnLeaf(Walk& w, uint32_t t, InPiece ps, int piece) {
  if (ps == InPiece::Above) ++figures_.constrainedLeaves;
  const bool textured = ps == InPiece::In;
  TerrainMesh& m = (*w.pass.meshes)[size_t(textured ? piece : w.untextured)];
  const LeafSink sink{.vertices = &m.vertices,
                      .indices = &m.indices,
                      .origin = m.origin,
                      .tile = textured ? &w.pass.pieces->tiles()[size_t(piece)] : nullptr,
                      .stamps = &stamps_,
                      .frame = outputFrame_,
                      .stamp = static_cast<uint32_t>(textured ? piece : w.untextured),
                      .chunkVertices = nullptr,
                      .counts = &w.emitted,
                      .morphing = nullptr};
  if (emitLeaf(mesh_, w.pass.timeS, t, sink)) ++figures_.drawnTriangles;
}

void RoamOutput::emitSeed(Walk& w, const SeedPlace& at, const glm::dvec3* world, const glm::dvec3* eye,
                          bool interpolated, int piece) {
  // The seeding horizon is measured to the nearest vertex (§3.1).
  const double nearest = std::min({glm::length(eye[0]), glm::length(eye[1]), glm::length(eye[2])});
  if (nearest > seeds_.horizonM) return;
  // Back faces are seeded too (unlike §3.1): plants stand up from ground that faces away — past
  // a crest their tops show above it — and dropping a triangle's plants the moment the camera
  // crosses its plane made them all pop at once (issue 18). The terrain's depth hides the rest,
  // and the Hi-Z occlusion test keeps them from being classified.
  const EyeView& view = *w.pass.view;
  SeedTriangle s;
  s.path = at.path;
  const std::array<glm::dvec3, 3> e{eye[0], eye[1], eye[2]};
  const double lod = seeds_.rule == PlantCountRule::ScreenArea ? plantCountScreen(view, e, seeds_, &s.nearPlane)
                                                               : plantCountWorld(view, e, seeds_);
  for (int i = 0; i < 3; ++i) {
    s.world[size_t(i)] = world[i];
    s.fromCamera[size_t(i)] = glm::vec3(world[i] - view.cameraEnu);
  }
  s.interpolated = interpolated;
  s.corners = at.corners;
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

void RoamOutput::refineSeeds(Walk& w, const SeedPlace& at, const glm::dvec3* world, const glm::dvec3* eye,
                             double thickness, int piece) {
  // Below a leaf coarser than the seed level: midpoint splits without the heightmap, world and
  // eye coordinates interpolated (rotations are linear: §3.1 B).
  if (cullWedgie(*w.pass.frustum, eye[0], eye[1], eye[2], thickness, thickness + options_.canopyM) == Cull::Outside)
    return;
  const glm::dvec3 c = 0.5 * (eye[1] + eye[2]);
  const double radius = std::max(glm::length(eye[0] - c), glm::length(eye[1] - c));
  if (glm::length(c) - radius - thickness > seeds_.horizonM) return;
  if (at.path.level == seedLevel_) {
    emitSeed(w, at, world, eye, true, piece);
    return;
  }
  const glm::dvec3 mw = 0.5 * (world[1] + world[2]), me = 0.5 * (eye[1] + eye[2]);
  const glm::dvec3 w0[3] = {mw, world[0], world[1]}, w1[3] = {mw, world[2], world[0]};
  const glm::dvec3 e0[3] = {me, eye[0], eye[1]}, e1[3] = {me, eye[2], eye[0]};
  refineSeeds(w, {childPath(at.path, 0), child(at.corners, 0)}, w0, e0, thickness, piece);
  refineSeeds(w, {childPath(at.path, 1), child(at.corners, 1)}, w1, e1, thickness, piece);
}

}  // namespace vegstream::terrain
