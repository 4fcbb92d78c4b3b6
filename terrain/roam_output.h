#pragma once
// RoamOutput (internal to the tessellator, roam_tessellator.h output()): the output traversal.
// The drawn leaves in eye space with hierarchical culling of the wedgie plus the canopy, one
// mesh per piece (+1: leaves not yet inside a piece, untextured), most of them as references to
// the drawn chunks (roam_chunks.h); and the seed triangles (seed_triangles.h) of the seed level
// within the horizon, refined by midpoint splits below a coarser leaf. Only each split's new
// vertex is transformed on the way down (§3.1 A); refined seed triangles interpolate their
// parents' eye coordinates (§3.1 B). It owns the drawn chunks (the output cache, roam_chunks.h)
// and the direct output's vertex stamps (which piece's mesh a vertex went into this output, and
// where); both follow a compaction's renumbering (compacted).
// Counts drawnTriangles, constrainedLeaves, morphingVertices, leavesEmitted, chunksMoved and the
// seed figures into the figures; marks the mesh shown.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "geo/local_frame.h"
#include "terrain/eye_space.h"
#include "terrain/roam_chunks.h"
#include "terrain/roam_leaves.h"
#include "terrain/roam_mesh.h"
#include "terrain/roam_priorities.h"
#include "terrain/roam_tessellator.h"
#include "terrain/seed_triangles.h"
#include "terrain/terrain_mesh.h"

namespace vegstream::terrain {

class RoamOutput {
 public:
  // Every reference outlives this.
  RoamOutput(RoamMesh& mesh, const geo::LocalFrame& frame, const RoamOptions& options, const SeedOptions& seeds,
             int seedLevel, RoamFigures& figures);

  // `attachChunks`: false while a compaction's copy reads the nodes (roam_chunks.h ChunkPass).
  void run(const EyeView& view, const PieceSet& pieces, double timeS, std::vector<TerrainMesh>& meshes,
           std::vector<SeedTriangle>& seeds, bool attachChunks);

  static constexpr uint64_t kChunkIdleFrames = DrawnChunks::kChunkIdleFrames;
  // Between outputs: the chunks whose root the mesh freed are released, and those unused for
  // kChunkIdleFrames outputs dropped.
  void dropIdleChunks() {
    chunks_.release();
    chunks_.dropIdle();
  }
  // The mesh was compacted: the chunks follow their roots; the stamps are of old vertex indices.
  void compacted(const RoamRenumbering& renumbering) {
    chunks_.remap(renumbering);
    stamps_.clear();
  }

 private:
  struct Walk;  // the state of one traversal
  void resetPieces(const EyeView& view, const PieceSet& pieces, std::vector<TerrainMesh>& meshes) const;
  void visit(Walk& w, uint32_t t, const glm::dvec3* eye, Cull cull, PlaneMask planes, InPiece ps, int piece,
             bool seeds);
  // The seed triangles at or below `t` (at or above the seed level, within reach); false: none
  // further down.
  bool seedsAt(Walk& w, uint32_t t, const glm::dvec3* eye, double thickness, InPiece ps, int piece);
  void emitDrawnLeaf(Walk& w, uint32_t t, InPiece ps, int piece);
  // A seed triangle's identity and its corners on the grid, handed down with it: the corners of a
  // path walked from its root cost a step per level, a tenth of the output's instructions.
  struct SeedPlace {
    TriPath path;
    TriCorners corners;
  };
  void emitSeed(Walk& w, const SeedPlace& at, const glm::dvec3* world, const glm::dvec3* eye, bool interpolated,
                int piece);
  void refineSeeds(Walk& w, const SeedPlace& at, const glm::dvec3* world, const glm::dvec3* eye, double thickness,
                   int piece);

  RoamMesh& mesh_;
  const geo::LocalFrame& frame_;
  const RoamOptions& options_;
  const SeedOptions& seeds_;
  const int seedLevel_;
  RoamFigures& figures_;
  DrawnChunks chunks_;
  std::vector<VertexStamp> stamps_;
  uint64_t outputFrame_ = 0;
};

}  // namespace vegstream::terrain
