// The tessellator's compactions (roam_tessellator.h, RoamOptions::tasks): RoamMesh::compact's
// copy on another thread while the frame goes on. A compaction copies every node and vertex in
// tree order — 2–11 ms at 80 k leaves, the slowest frames of a flight when it ran in the update
// (issue 17) — and nothing needs its result until the next change of the mesh: the output only
// reads the mesh, and the rest of the frame does not touch it.

#include <atomic>
#include <cassert>
#include <condition_variable>
#include <mutex>

#include "core/stopwatch.h"
#include "terrain/roam_tessellator.h"
#include "terrain/roam_walk.h"  // the scratch types the destructor destroys

namespace vegstream::terrain {

struct RoamTessellator::PendingCompaction {
  const RoamMesh* mesh = nullptr;
  TaskRunner* tasks = nullptr;  // the copy's subtrees run there too (RoamMesh::buildCompaction)
  RoamCompaction work;
  std::atomic<bool> claimed{false};  // the worker or finishCompaction: the first one makes the copy
  std::mutex mu;
  std::condition_variable doneCv;
  bool done = false;

  void build() {
    mesh->buildCompaction(work, tasks);
    std::lock_guard lock(mu);
    done = true;
    doneCv.notify_all();
  }
};

RoamTessellator::~RoamTessellator() {
  // A worker may be copying from the mesh: it must be done first. One that has not started
  // never will (the claim is taken here).
  if (compaction_ && compaction_->claimed.exchange(true)) {
    std::unique_lock lock(compaction_->mu);
    compaction_->doneCv.wait(lock, [&] { return compaction_->done; });
  }
}

void RoamTessellator::startCompaction() {
  assert(!compaction_);
  if (!options_.tasks) {
    remapChunks(mesh_.compact());
    stamps_.clear();
    return;
  }
  compaction_ = std::make_shared<PendingCompaction>();
  compaction_->mesh = &mesh_;
  compaction_->tasks = options_.tasks;
  compaction_->work = mesh_.beginCompaction();
  options_.tasks->post([pending = compaction_] {
    if (!pending->claimed.exchange(true)) pending->build();
  });
}

void RoamTessellator::finishCompaction() {
  if (!compaction_) return;
  Stopwatch watch;
  PendingCompaction& pending = *compaction_;
  if (!pending.claimed.exchange(true)) {
    pending.build();  // no worker took it (a busy runner): the copy is made here
  } else {
    std::unique_lock lock(pending.mu);
    pending.doneCv.wait(lock, [&] { return pending.done; });
  }
  remapChunks(mesh_.endCompaction(std::move(pending.work)));
  stamps_.clear();
  compaction_.reset();
  compactWaitMs_ += watch.elapsedMs();  // this update's figure (update() hands it on)
}

}  // namespace vegstream::terrain
