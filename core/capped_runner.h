#pragma once
// CappedRunner: a TaskRunner that hands its tasks to another one but offers at most `cap` of
// them at once to the loops that size themselves by concurrency() (parallelFor, parallelEach).
// The frame's short parallel loops — ROAM's priorities and chunks, the terrain's per-frame copies
// — run on one: on a 16-core host, a loop of a few hundred microseconds that woke all 16 workers
// spent more in the wake-ups and in the shared index than in its work (perf on the GPU host:
// bench/README.md, "The CPU frame on the GPU host, profiled"). Long-running tasks and the work sized
// otherwise (the streamer's decodes) keep the whole runner.

#include <algorithm>
#include <cassert>
#include <utility>

#include "core/task_runner.h"

namespace vegstream {

class CappedRunner final : public TaskRunner {
 public:
  CappedRunner(TaskRunner& runner, int cap) : runner_(&runner), cap_(cap) { assert(cap >= 1); }
  void post(Task task) override { runner_->post(std::move(task)); }
  void postLongRunning(Task task) override { runner_->postLongRunning(std::move(task)); }
  int concurrency() const override { return std::min(cap_, runner_->concurrency()); }

 private:
  TaskRunner* runner_;
  int cap_;
};

}  // namespace vegstream
