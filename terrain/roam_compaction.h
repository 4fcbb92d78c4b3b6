#pragma once
// RoamCompactor (internal to the tessellator, RoamOptions::tasks): RoamMesh::compact's copy on
// another thread while the frame goes on. A compaction copies every node and vertex in tree
// order — 2–11 ms at 80 k leaves, the slowest frames of a flight when it ran in the update
// (issue 17) — and nothing needs its result until the next change of the mesh: the output only
// reads the mesh, and the rest of the frame does not touch it. It owns the compaction under way.
//
// Contract: start() at the end of an update; with a task runner the copy is posted and finish()
// — before anything changes the mesh — waits for it (or makes it itself if no worker has taken
// it yet; it copies beside the worker rather than idle) and applies it; without one, start()
// compacts at once. Either hands back the renumbering: the caller moves what holds node or
// vertex indices (the drawn chunks, the output's stamps). The destructor waits for a copy under
// way (one not started never will be).

#include <memory>
#include <optional>

#include "core/task_runner.h"
#include "terrain/roam_mesh.h"

namespace vegstream::terrain {

class RoamCompactor {
 public:
  // `mesh` outlives this; `tasks` (may be null) too.
  RoamCompactor(RoamMesh& mesh, TaskRunner* tasks);
  ~RoamCompactor();
  RoamCompactor(const RoamCompactor&) = delete;
  RoamCompactor& operator=(const RoamCompactor&) = delete;

  // A copy started and not yet applied.
  bool pending() const { return pending_ != nullptr; }
  // None pending. The renumbering when the mesh was compacted at once (no task runner).
  std::optional<RoamRenumbering> start();
  // One pending: waits for its copy, applies it, returns the renumbering.
  RoamRenumbering finish();

 private:
  struct Pending;
  RoamMesh& mesh_;
  TaskRunner* tasks_;
  std::shared_ptr<Pending> pending_;
};

}  // namespace vegstream::terrain
