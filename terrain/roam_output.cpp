// ROAM output traversal: drawn leaves per piece and seed triangles (roam_tessellator.h). Seed
// 001_3eca9f2c7752e4fb.txt §3.1 (what to seed: fixed level, frustum, horizon, back faces;
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
  beginView(view);
  stamps_.resize(mesh_.vertexCapacity());
  meshes.resize(pieces.tiles().size() + 1);
  for (size_t i = 0; i < meshes.size(); ++i) {
    TerrainMesh& m = meshes[i];
    m.vertices.clear();
    m.indices.clear();
    if (i < pieces.tiles().size()) {
      const geo::TileId& t = pieces.tiles()[i];
      const glm::dvec2 c = geo::tileXYToLonLat({t.x + 0.5, t.y + 0.5}, t.z);
      m.origin = frame_.toLocal({c.y, c.x, mesh_.options().fillHeightM});
    } else {
      m.origin = view.cameraEnu;
    }
  }
  seeds.clear();
  Walk w;
  w.view = &view;
  w.pieces = &pieces;
  w.timeS = timeS;
  w.meshes = &meshes;
  w.seeds = &seeds;
  w.untextured = static_cast<int>(pieces.tiles().size());
  figures_.drawnTriangles = figures_.constrainedLeaves = figures_.morphingVertices = 0;
  figures_.seedTriangles = figures_.seedInterpolated = 0;
  figures_.seedPlants = 0.0;
  figures_.achievedErrorPx = 0.0;
  figures_.depthLimitedLeaves = 0;
  for (uint32_t r : mesh_.roots()) {
    glm::dvec3 eye[3];
    eyeOf(view, r, eye);
    visitOutput(w, r, eye, Cull::Partial, InPiece::None, -1, true);
  }
  figures_.seedTriangles = seeds.size();
  figures_.outputMs = watch.elapsedMs();
}

void RoamTessellator::visitOutput(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, InPiece ps, int piece,
                                  bool seeds) {
  const RoamNode& n = mesh_.node(t);
  const int level = n.path.level;
  const double e = std::max(0.0f, n.thickness == n.thickness ? n.thickness : 0.0f);
  if (cull != Cull::Inside) {
    cull = cullWedgie(*w.view, eye[0], eye[1], eye[2], e, e + options_.canopyM);
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
        if (level == seedLevel_) emitSeed(w, n.path, world, eye, false, seedPiece);
        else refineSeeds(w, n.path, world, eye, e, seedPiece);
      }
      seeds = false;
    }
  }
  if (n.isLeaf()) {
    if (cull != Cull::Outside) {
      const double px = n.thickness >= 0.0f ? projectedErrorPx(*w.view, t, eye, n.thickness) : 0.0;
      figures_.achievedErrorPx = std::max(figures_.achievedErrorPx, px);
      if (px > options_.maxErrorPx && level >= mesh_.grid().maxLevel()) ++figures_.depthLimitedLeaves;
    }
    if (ps == InPiece::Above) ++figures_.constrainedLeaves;
    emitLeaf(w, t, ps == InPiece::In ? piece : w.untextured);
    return;
  }
  const uint32_t c = n.child;
  const glm::dvec3 m = eyeOfVertex(*w.view, n.mid);  // the only vertex transformed here (§3.1 A)
  const glm::dvec3 e0[3] = {m, eye[0], eye[1]}, e1[3] = {m, eye[2], eye[0]};
  visitOutput(w, c, e0, cull, ps, piece, seeds);
  visitOutput(w, c + 1, e1, cull, ps, piece, seeds);
}

void RoamTessellator::emitLeaf(Walk& w, uint32_t t, int piece) {
  const RoamNode& n = mesh_.node(t);
  for (uint32_t v : n.v)
    if (!(mesh_.vertex(v).heightM == mesh_.vertex(v).heightM)) return;  // nodata: a hole, never a drop to 0
  TerrainMesh& m = (*w.meshes)[size_t(piece)];
  const bool textured = piece != w.untextured;
  const geo::TileId tile = textured ? w.pieces->tiles()[size_t(piece)] : geo::TileId{};
  const double uvScale = std::ldexp(1.0, tile.z - mesh_.grid().gridZoom());
  for (uint32_t v : n.v) {
    Stamp& st = stamps_[v];
    if (st.frame == outputFrame_ && st.piece == uint32_t(piece)) {
      m.indices.push_back(st.index);
      continue;
    }
    const RoamVertex& x = mesh_.vertex(v);
    const double h = x.drawnHeight(w.timeS, mesh_.options().fadeS);
    if (h != x.heightM) ++figures_.morphingVertices;
    TerrainVertex out;
    out.position = glm::vec3(x.position(h) - m.origin);
    out.normal = x.normal;
    out.heightMsl = static_cast<float>(h);
    if (textured) out.uv = glm::vec2(double(x.grid.x) * uvScale - tile.x, double(x.grid.y) * uvScale - tile.y);
    st = {outputFrame_, uint32_t(piece), static_cast<uint32_t>(m.vertices.size())};
    m.indices.push_back(st.index);
    m.vertices.push_back(out);
  }
  ++figures_.drawnTriangles;
}

void RoamTessellator::emitSeed(Walk& w, const TriPath& path, const glm::dvec3* world, const glm::dvec3* eye,
                               bool interpolated, int piece) {
  // The seeding horizon is measured to the nearest vertex (§3.1).
  const double nearest = std::min({glm::length(eye[0]), glm::length(eye[1]), glm::length(eye[2])});
  if (nearest > seeds_.horizonM) return;
  // Back faces: the ground faces away when the camera is below its plane.
  if (glm::dot(glm::cross(eye[1] - eye[0], eye[2] - eye[0]), eye[0]) > 0.0) return;
  SeedTriangle s;
  s.path = path;
  const std::array<glm::dvec3, 3> e{eye[0], eye[1], eye[2]};
  s.plantCount = static_cast<float>(seeds_.rule == PlantCountRule::ScreenArea
                                        ? plantCountScreen(*w.view, e, seeds_, &s.nearPlane)
                                        : plantCountWorld(*w.view, e, seeds_));
  for (int i = 0; i < 3; ++i) {
    s.world[size_t(i)] = world[i];
    s.fromCamera[size_t(i)] = glm::vec3(world[i] - w.view->cameraEnu);
  }
  s.interpolated = interpolated;
  s.corners = mesh_.grid().corners(path);
  s.piece = piece;
  figures_.seedPlants += s.plantCount;
  if (interpolated) ++figures_.seedInterpolated;
  w.seeds->push_back(s);
}

void RoamTessellator::refineSeeds(Walk& w, const TriPath& path, const glm::dvec3* world, const glm::dvec3* eye,
                                  double thickness, int piece) {
  // Below a leaf coarser than the seed level: midpoint splits without the heightmap, world and
  // eye coordinates interpolated (rotations are linear: §3.1 B).
  if (cullWedgie(*w.view, eye[0], eye[1], eye[2], thickness, thickness + options_.canopyM) == Cull::Outside) return;
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
