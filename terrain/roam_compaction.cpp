// The tessellator's compactions (roam_tessellator.h, RoamOptions::tasks): RoamMesh::compact's
// copy on another thread while the frame goes on. A compaction copies every node and vertex in
// tree order — 2–11 ms at 80 k leaves, the slowest frames of a flight when it ran in the update
// (issue 17) — and nothing needs its result until the next change of the mesh: the output only
// reads the mesh, and the rest of the frame does not touch it.

#include <atomic>
#include <cassert>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>

#include "core/stopwatch.h"
#include "terrain/roam_tessellator.h"
#include "terrain/roam_walk.h"  // the scratch types the destructor destroys

namespace vegstream::terrain {

// The copy's own runner: RoamMesh::buildCompaction splits it over subtrees with parallelFor,
// whose helper tasks go to the pool and also to a queue of this copy's, each run once by
// whichever gets to it first. The thread that waits for the copy (finishCompaction) runs them
// from the queue instead of idling: the copy starts on a worker at the end of an update, and when
// it is not done by the next one — in a fast descent the frame has little else to do on a small
// machine — the frame thread copies beside that worker rather than wait for it alone.
struct RoamTessellator::PendingCompaction final : TaskRunner {
  struct Helper {
    Task task;
    std::atomic<bool> taken{false};
    void run() {
      if (!taken.exchange(true)) task();
    }
  };

  const RoamMesh* mesh = nullptr;
  TaskRunner* pool = nullptr;  // the copy's helpers run there too
  RoamCompaction work;
  std::atomic<bool> claimed{false};  // the worker or finishCompaction: the first one makes the copy
  std::mutex mu;
  std::condition_variable changed;  // a helper queued, or the copy done
  std::deque<std::shared_ptr<Helper>> helpers;
  bool done = false;

  void post(Task task) override {
    auto helper = std::make_shared<Helper>();
    helper->task = std::move(task);
    {
      std::lock_guard lock(mu);
      helpers.push_back(helper);
    }
    changed.notify_all();
    pool->post([helper] { helper->run(); });
  }
  void postLongRunning(Task task) override { pool->postLongRunning(std::move(task)); }
  // The pool's workers and the thread waiting for the copy.
  int concurrency() const override { return pool->concurrency() + 1; }

  void build() {
    mesh->buildCompaction(work, this);
    std::lock_guard lock(mu);
    done = true;
    changed.notify_all();
  }
  // Until the copy is done: runs its queued helpers (a helper that a worker took first does
  // nothing here), else waits for one or for the end.
  void helpUntilDone() {
    std::unique_lock lock(mu);
    while (!done) {
      if (helpers.empty()) {
        changed.wait(lock);
        continue;
      }
      const std::shared_ptr<Helper> helper = std::move(helpers.front());
      helpers.pop_front();
      lock.unlock();
      helper->run();
      lock.lock();
    }
    helpers.clear();
  }
};

RoamTessellator::~RoamTessellator() {
  // A worker may be copying from the mesh: it must be done first. One that has not started
  // never will (the claim is taken here).
  if (compaction_ && compaction_->claimed.exchange(true)) compaction_->helpUntilDone();
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
  compaction_->pool = options_.tasks;
  compaction_->work = mesh_.beginCompaction();
  options_.tasks->post([pending = compaction_] {
    if (!pending->claimed.exchange(true)) pending->build();
  });
}

void RoamTessellator::finishCompaction() {
  if (!compaction_) return;
  Stopwatch watch;
  PendingCompaction& pending = *compaction_;
  if (!pending.claimed.exchange(true))
    pending.build();  // no worker took it (a busy runner): the copy is made here
  else
    pending.helpUntilDone();
  remapChunks(mesh_.endCompaction(std::move(pending.work)));
  stamps_.clear();
  compaction_.reset();
  compactWaitMs_ += watch.elapsedMs();  // this update's figure (update() hands it on)
}

}  // namespace vegstream::terrain
