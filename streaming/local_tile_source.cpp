// LocalTileSource (local_tile_source.h): a queue of read requests served by at most
// `ioConcurrency` tasks at once, each taking requests until the queue is empty. Cancelled
// requests are answered by the tasks too (never inside cancel()), so a callback never
// re-enters the caller.

#include "streaming/local_tile_source.h"

#include <algorithm>
#include <cassert>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <unordered_set>
#include <vector>

#include "core/regular_file.h"

namespace vegstream::streaming {
namespace {
namespace fs = std::filesystem;

struct Job {
  RequestId id = 0;
  std::string relativePath;
  FetchCallback done;
  bool cancelled = false;
  bool outsideRoot = false;  // absolute or "..": failed without touching the disk
};

// A relative path that stays inside the dataset: no root, no "..".
bool isInsideRoot(const std::string& relativePath) {
  const fs::path p(relativePath);
  if (relativePath.empty() || p.is_absolute() || p.has_root_name()) return false;
  return std::none_of(p.begin(), p.end(), [](const fs::path& part) { return part == ".."; });
}

// Reads the whole file through the checked opener (core/regular_file.h): a missing file is
// Missing; no regular file, one past the tile ceiling, or a failed read is Failed, at once.
FetchResult readWholeFile(const fs::path& path) {
  FetchResult r;
  r.attempts = 1;
  auto bytes = readRegularFileBytes(path, kTileFileCeiling, "no such file");
  if (!bytes) {
    r.outcome = bytes.error().kind == ErrorKind::NotFound ? FetchOutcome::Missing : FetchOutcome::Failed;
    r.permanent = bytes.error().kind == ErrorKind::InvalidInput;  // what the path is: no retry changes it
    r.message = bytes.error().message;
    return r;
  }
  r.bytes = std::move(*bytes);
  r.outcome = FetchOutcome::Ok;
  return r;
}

}  // namespace

struct LocalTileSource::Impl : std::enable_shared_from_this<Impl> {
  fs::path root;
  TaskRunner* runner = nullptr;
  int maxTasks = 2;
  mutable std::mutex mu;
  std::condition_variable idle;           // the destructor waits here for `busy` to reach 0
  std::deque<Job> queue;                  // waiting to be read (cancelled ones are answered first)
  std::unordered_set<RequestId> reading;  // being read right now
  std::unordered_set<RequestId> cancelWhileReading;
  std::size_t inFlight = 0;  // started, not yet called back
  SourceCounters counters;
  bool stopping = false;
  int tasks = 0;  // read tasks posted and not finished
  int busy = 0;   // read tasks running right now

  // Called with `mu` held: a task more if the queue has work and the limit allows.
  void postTaskLocked() {
    if (tasks >= maxTasks || queue.empty()) return;
    ++tasks;
    postLocked();
  }
  void postLocked() {
    runner->post([self = shared_from_this()] { self->run(); });
  }

  // One task answers one request, then posts itself again while requests are queued (so the
  // runner interleaves it with other work, and a ManualTaskRunner steps one read at a time).
  void run() {
    std::unique_lock lock(mu);
    ++busy;
    if (!queue.empty() && !stopping) {  // when stopping, the destructor answers what is left
      Job job = std::move(queue.front());
      queue.pop_front();
      FetchResult r;
      r.id = job.id;
      if (job.cancelled) {
        r.outcome = FetchOutcome::Cancelled;
      } else if (job.outsideRoot) {
        r.outcome = FetchOutcome::Failed;
        r.attempts = 1;
        r.message = "'" + job.relativePath + "' is not a path inside the dataset directory";
      } else {
        reading.insert(job.id);
        lock.unlock();
        r = readWholeFile(root / job.relativePath);
        r.id = job.id;
        lock.lock();
        reading.erase(job.id);
        if (cancelWhileReading.erase(job.id) > 0) {
          r.outcome = FetchOutcome::Cancelled;
          r.bytes.clear();
        }
      }
      countOutcome(counters, r.outcome, r.bytes.size());
      // The callback runs unlocked (it may take its own locks); inFlight drops after it, so a
      // caller that sees inFlight() == 0 knows every callback has returned.
      lock.unlock();
      job.done(std::move(r));
      lock.lock();
      --inFlight;
    }
    if (!queue.empty() && !stopping)
      postLocked();
    else
      --tasks;
    if (--busy == 0) idle.notify_all();
  }
};

LocalTileSource::LocalTileSource(fs::path datasetDir, int ioConcurrency, TaskRunner* tasks)
    : impl_(std::make_shared<Impl>()) {
  assert(ioConcurrency >= 1);
  if (!tasks) {
    ownPool_ = std::make_unique<ThreadPool>(ioConcurrency);
    tasks = ownPool_.get();
  }
  impl_->root = std::move(datasetDir);
  impl_->runner = tasks;
  impl_->maxTasks = ioConcurrency;
}

LocalTileSource::~LocalTileSource() {
  std::deque<Job> left;
  {
    std::unique_lock lock(impl_->mu);
    impl_->stopping = true;
    // Reads under way finish (their callbacks run); tasks that have not started find nothing.
    impl_->idle.wait(lock, [&] { return impl_->busy == 0; });
    left.swap(impl_->queue);
    impl_->counters.requestsCancelled += left.size();
  }
  for (Job& job : left) {
    FetchResult r;
    r.id = job.id;
    r.outcome = FetchOutcome::Cancelled;
    job.done(std::move(r));
    std::lock_guard lock(impl_->mu);
    --impl_->inFlight;
  }
  // ownPool_ (declared first) is destroyed after this body: its tasks, if any, return at once.
}

std::string LocalTileSource::describe() const { return "dir " + impl_->root.string(); }

Result<std::string> LocalTileSource::readText(const std::string& relativePath) {
  if (!isInsideRoot(relativePath))
    return makeError(ErrorKind::InvalidInput, "'" + relativePath + "' is not a path inside the dataset directory");
  // dataset.json has its own ceiling; everything else read this way is a tile (the snapshot).
  const bool meta = fs::path(relativePath).filename() == "dataset.json";
  return readRegularFile(impl_->root / relativePath, meta ? kDatasetJsonCeiling : kTileFileCeiling);
}

void LocalTileSource::start(RequestId id, const std::string& relativePath, FetchCallback done) {
  assert(done);
  // A bad path is answered by an I/O thread like every other outcome.
  Job job{id, relativePath, std::move(done), false, !isInsideRoot(relativePath)};
  {
    std::lock_guard lock(impl_->mu);
    ++impl_->counters.requestsStarted;
    ++impl_->inFlight;
    impl_->queue.push_back(std::move(job));
    impl_->postTaskLocked();
  }
}

void LocalTileSource::cancel(RequestId id) {
  std::lock_guard lock(impl_->mu);
  auto it = std::find_if(impl_->queue.begin(), impl_->queue.end(), [&](const Job& j) { return j.id == id; });
  if (it != impl_->queue.end()) {
    // Moved to the front so the answer comes at once rather than after the reads queued before it.
    Job job = std::move(*it);
    impl_->queue.erase(it);
    job.cancelled = true;
    impl_->queue.push_front(std::move(job));
  } else if (impl_->reading.count(id) > 0) {
    impl_->cancelWhileReading.insert(id);
  }
}

std::size_t LocalTileSource::inFlight() const {
  std::lock_guard lock(impl_->mu);
  return impl_->inFlight;
}

SourceCounters LocalTileSource::counters() const {
  std::lock_guard lock(impl_->mu);
  return impl_->counters;
}

}  // namespace vegstream::streaming
