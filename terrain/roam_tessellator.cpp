// RoamTessellator (roam_tessellator.h): the owner of the ROAM mesh and of the parts that work on
// it, and the order they run in. Seed 001_3eca9f2c7752e4fb.txt §3.1; Duchaineau et al. 1997 §6.
//   update():  RoamPriorities (roam_priorities.h), the priority traversal; RoamQueues
//              (roam_queues.h), the split and merge queues; RoamCompactor (roam_compaction.h),
//              the pools put back in depth-first order now and then.
//   output():  RoamOutput (roam_output.h), the output traversal and the seed triangles, with
//              the drawn chunks it keeps between outputs (roam_chunks.h).

#include "terrain/roam_tessellator.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <utility>

#include "core/stopwatch.h"
#include "terrain/roam_compaction.h"
#include "terrain/roam_output.h"
#include "terrain/roam_priorities.h"
#include "terrain/roam_queues.h"

namespace vegstream::terrain {

void PieceSet::assign(std::span<const geo::TileId> tiles) {
  tiles_.assign(tiles.begin(), tiles.end());
  index_.clear();
  above_.clear();
  minZoom_ = std::numeric_limits<int>::max();
  maxZoom_ = -1;
  for (size_t i = 0; i < tiles_.size(); ++i) {
    const geo::TileId& t = tiles_[i];
    index_.emplace(pack(t), static_cast<int>(i));
    minZoom_ = std::min(minZoom_, t.z);
    maxZoom_ = std::max(maxZoom_, t.z);
    for (int z = t.z - 1; z >= 0; --z) {
      const int k = t.z - z;
      if (!above_.insert(pack({z, t.x >> k, t.y >> k})).second) break;  // its ancestors are in already
    }
  }
}

int PieceSet::pieceOf(const geo::TileId& square) const {
  // Only the zooms pieces are at: a new leaf asks this, and most pieces are at one or two zooms.
  for (int z = std::min(square.z, maxZoom_); z >= minZoom_; --z) {
    const int k = square.z - z;
    const int i = exactly({z, square.x >> k, square.y >> k});
    if (i >= 0) return i;
  }
  return -1;
}

RoamTessellator::RoamTessellator(BintreeGrid grid, geo::TileRange roots, const geo::LocalFrame& frame,
                                 ResidentHeights& heights, RoamOptions options, SeedOptions seeds,
                                 RoamMeshOptions meshOptions, double seedLatitudeDeg)
    : mesh_(grid, roots, frame, heights, meshOptions), frame_(frame), options_(options), seeds_(seeds),
      seedLevel_(seedLevelFor(grid, seedLatitudeDeg, seeds.targetAreaM2)),
      priorities_(std::make_unique<RoamPriorities>(mesh_, options_, seeds_, seedLevel_)),
      queues_(std::make_unique<RoamQueues>(mesh_, options_, *priorities_, figures_)),
      output_(std::make_unique<RoamOutput>(mesh_, frame_, options_, seeds_, seedLevel_, figures_)),
      compactor_(std::make_unique<RoamCompactor>(mesh_, options_.tasks)) {
  mesh_.reserve(options_.maxTriangles);
}

// The compactor goes first (declared last): a worker may be copying from the mesh.
RoamTessellator::~RoamTessellator() = default;

void RoamTessellator::tilesChanged(std::span<const streaming::TileKey> keys) {
  if (keys.empty()) return;
  finishCompaction();
  for (const streaming::TileKey& k : keys)
    if (k.layer == streaming::TileLayer::Height) mesh_.resample(k.id);
}

double RoamTessellator::errorPx(const EyeView& view, uint32_t t) const { return priorities_->errorPx(view, t); }

void RoamTessellator::update(const EyeView& view, const PieceSet& pieces, double timeS) {
  Stopwatch watch;
  figures_ = {};
  finishCompaction();
  figures_.compactWaitMs = std::exchange(compactWaitMs_, 0.0);
  mesh_.setTime(timeS);
  priorities_->begin(view);
  std::vector<Candidate> splits, diamonds;
  const Frustum frustum(view);
  const double started = watch.elapsedMs();  // the compaction's wait and begin() before it
  priorities_->compute(view, frustum, pieces, splits, diamonds, figures_);
  const double visited = watch.elapsedMs();
  figures_.prioritiesMs = visited - started;
  uint64_t ops = 0;
  queues_->split(view, frustum, pieces, splits, ops, watch);
  const double split = watch.elapsedMs();
  figures_.splitMs = split - visited;
  queues_->merge(diamonds, timeS, ops, watch);
  const double merged = watch.elapsedMs();
  figures_.mergeMs = merged - split;
  // The pools are put back in depth-first order (cache locality) once the splits since the last
  // time have allocated 1 / kCompactChurn as many node pairs as are live: that is what scatters
  // them (a compaction costs milliseconds, so it waits for churn, not for a number of frames).
  // At the end of the update: with a task runner its copy goes on beside the output and the rest
  // of the frame, and the next update applies it; without one, this update makes it and this
  // frame's output walks the compacted pools.
  const bool compact = mesh_.pairsAllocatedSinceCompact() * kCompactChurn >= mesh_.livePairs();
  if (++updates_ % RoamOutput::kChunkIdleFrames == 0 || compact) output_->dropIdleChunks();
  if (compact) {
    startCompaction();
    figures_.compacted = true;
  }
  figures_.compactMs = watch.elapsedMs() - merged;
  figures_.leaves = mesh_.leafCount();
  figures_.updateMs = watch.elapsedMs();
}

void RoamTessellator::output(const EyeView& view, const PieceSet& pieces, double timeS,
                             std::vector<TerrainMesh>& meshes, std::vector<SeedTriangle>& seeds) {
  Stopwatch watch;
  output_->run(view, pieces, timeS, meshes, seeds, !compactor_->pending());
  figures_.outputMs = watch.elapsedMs();
}

void RoamTessellator::startCompaction() {
  if (const std::optional<RoamRenumbering> renumbering = compactor_->start()) output_->compacted(*renumbering);
}

void RoamTessellator::finishCompaction() {
  if (!compactor_->pending()) return;
  Stopwatch watch;
  output_->compacted(compactor_->finish());
  compactWaitMs_ += watch.elapsedMs();  // this update's figure (update() hands it on)
}

}  // namespace vegstream::terrain
