// RoamCompactor (roam_compaction.h): the tessellator's compactions, their copy on
// RoamOptions::tasks beside the frame.

#include "terrain/roam_compaction.h"

#include <atomic>
#include <cassert>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <utility>

namespace vegstream::terrain {

// The copy's own runner: RoamMesh::buildCompaction splits it over subtrees with parallelFor,
// whose helper tasks go to the pool and also to a queue of this copy's, each run once by
// whichever gets to it first. The thread that waits for the copy (finish) runs them from the
// queue instead of idling: the copy starts on a worker at the end of an update, and when it is
// not done by the next one — in a fast descent the frame has little else to do on a small
// machine — the frame thread copies beside that worker rather than wait for it alone.
struct RoamCompactor::Pending final : TaskRunner {
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
  std::atomic<bool> claimed{false};  // the worker or finish(): the first one makes the copy
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

RoamCompactor::RoamCompactor(RoamMesh& mesh, TaskRunner* tasks) : mesh_(mesh), tasks_(tasks) {}

RoamCompactor::~RoamCompactor() {
  // A worker may be copying from the mesh: it must be done first. One that has not started
  // never will (the claim is taken here).
  if (pending_ && pending_->claimed.exchange(true)) pending_->helpUntilDone();
}

std::optional<RoamRenumbering> RoamCompactor::start() {
  assert(!pending_);
  if (!tasks_) return mesh_.compact();
  pending_ = std::make_shared<Pending>();
  pending_->mesh = &mesh_;
  pending_->pool = tasks_;
  pending_->work = mesh_.beginCompaction();
  tasks_->post([pending = pending_] {
    if (!pending->claimed.exchange(true)) pending->build();
  });
  return std::nullopt;
}

RoamRenumbering RoamCompactor::finish() {
  assert(pending_);
  Pending& pending = *pending_;
  if (!pending.claimed.exchange(true))
    pending.build();  // no worker took it (a busy runner): the copy is made here
  else
    pending.helpUntilDone();
  RoamRenumbering renumbering = mesh_.endCompaction(std::move(pending.work));
  pending_.reset();
  return renumbering;
}

}  // namespace vegstream::terrain
