// DecodePipeline (decode_pipeline.h): one mutex guards the job queue, the completions and the
// cancel marks; decoding itself runs unlocked.

#include "streaming/decode_pipeline.h"

#include <algorithm>
#include <cassert>
#include <exception>

#include "datasets/landcover.h"

namespace vegstream::streaming::detail {

DecodePipeline::DecodePipeline(datasets::ElevationEncoding encoding, int tileSize, TaskRunner& runner,
                               int maxConcurrent, HeightExtraFn heightExtra)
    : encoding_(encoding), tileSize_(tileSize), heightExtra_(std::move(heightExtra)), runner_(runner),
      maxConcurrent_(maxConcurrent) {
  assert(maxConcurrent >= 1);
}

DecodePipeline::~DecodePipeline() { assert(closed_ && decoding_.empty()); }

void DecodePipeline::stop() {
  std::unique_lock lock(mu_);
  closed_ = true;
  jobs_.clear();
  completions_.clear();
  completionsCv_.notify_all();
  // Tasks not started yet return at once when they run; those decoding now are waited for.
  idleCv_.wait(lock, [&] { return decoding_.empty(); });
}

void DecodePipeline::pushLocked(Completion&& c) {
  completions_.push_back(std::move(c));
  completionsCv_.notify_all();
}

void DecodePipeline::onFetched(const TileKey& key, const std::string& name, FetchResult&& result,
                               CompanionBytes companions) {
  std::lock_guard lock(mu_);
  if (closed_) return;
  if (cancelled_.erase(result.id) > 0) return;  // the frame thread no longer wants it
  Completion c;
  c.id = result.id;
  c.attempts = result.attempts;
  c.permanent = result.permanent;
  c.message = std::move(result.message);
  switch (result.outcome) {
    case FetchOutcome::Ok:
      c.kind = Completion::Kind::Fetched;
      c.bytes = result.bytes.size() + companions.size();
      jobs_.push_back(Job{result.id, key, name, std::move(result.bytes), std::move(companions)});
      if (tasks_ < maxConcurrent_) {
        ++tasks_;
        runner_.post([self = shared_from_this()] { self->drain(); });
      }
      break;
    case FetchOutcome::Missing: c.kind = Completion::Kind::Missing; break;
    case FetchOutcome::Failed: c.kind = Completion::Kind::FetchFailed; break;
    case FetchOutcome::Cancelled: c.kind = Completion::Kind::Cancelled; break;
  }
  pushLocked(std::move(c));
}

void DecodePipeline::cancel(RequestId id) {
  std::lock_guard lock(mu_);
  if (closed_) return;
  bool finalRemoved = false;
  std::erase_if(completions_, [&](const Completion& c) {
    if (c.id != id) return false;
    finalRemoved = finalRemoved || c.kind != Completion::Kind::Fetched;
    return true;
  });
  if (finalRemoved) return;  // nothing more will come for it
  const auto job = std::find_if(jobs_.begin(), jobs_.end(), [&](const Job& j) { return j.id == id; });
  if (job != jobs_.end()) {
    jobs_.erase(job);
    return;
  }
  // At the source, or being decoded: whichever arrives next is dropped.
  cancelled_.insert(id);
}

std::vector<Completion> DecodePipeline::takeCompletions() {
  std::lock_guard lock(mu_);
  std::vector<Completion> out;
  out.swap(completions_);
  return out;
}

bool DecodePipeline::waitForCompletions(std::chrono::duration<double> timeout) {
  std::unique_lock lock(mu_);
  return completionsCv_.wait_for(lock, timeout, [&] { return closed_ || !completions_.empty(); }) && !closed_;
}

std::size_t DecodePipeline::decodesQueued() const {
  std::lock_guard lock(mu_);
  return jobs_.size() + decoding_.size();
}

// The companion layers' tiles of imagery tile `tile` (paired_fetch.h), each checked as its own
// layer's tile of the same id; absent bytes leave that layer empty.
Status DecodePipeline::decodeCompanions(const Job& job, datasets::ColorTile& tile) const {
  const auto& ndvi = job.companions.bytes[static_cast<size_t>(Companion::Ndvi)];
  if (!ndvi.empty()) {
    auto v = datasets::decodeNdviTile(ndvi, job.key.id, job.companions.names[static_cast<size_t>(Companion::Ndvi)],
                                      tileSize_);
    if (!v) return v.error();
    tile.ndvi = std::move(*v);
  }
  const auto& landcover = job.companions.bytes[static_cast<size_t>(Companion::Landcover)];
  if (!landcover.empty()) {
    auto v = datasets::decodeLandcoverTile(landcover, job.key.id,
                                           job.companions.names[static_cast<size_t>(Companion::Landcover)], tileSize_);
    if (!v) return v.error();
    tile.landcover = std::move(v->classes);
  }
  return {};
}

Completion DecodePipeline::decode(Job& job) const {
  Completion c;
  c.id = job.id;
  try {
    if (job.key.layer == TileLayer::Height) {
      auto t = datasets::decodeHeightTile(job.bytes, job.key.id, encoding_, tileSize_, job.name);
      if (t) {
        c.heights = std::make_shared<const datasets::HeightTile>(std::move(t).value());
        if (heightExtra_) c.extra = heightExtra_(*c.heights);
      } else {
        c.message = t.error().message;
      }
    } else {
      auto t = datasets::decodeColorTile(job.bytes, job.key.id, tileSize_, job.name);
      Status companions = t ? decodeCompanions(job, *t) : Status{};
      if (t && companions) {
        c.colors = std::make_shared<const datasets::ColorTile>(std::move(t).value());
      } else {
        c.message = t ? companions.error().message : t.error().message;
      }
    }
  } catch (const std::exception& e) {  // out of memory in the decoder: a failed tile, not a dead thread
    c.message = job.name + ": " + e.what();
  }
  c.kind = c.heights || c.colors ? Completion::Kind::Decoded : Completion::Kind::DecodeFailed;
  return c;
}

void DecodePipeline::drain() {
  std::unique_lock lock(mu_);
  if (!closed_ && !jobs_.empty()) {
    Job job = std::move(jobs_.front());
    jobs_.pop_front();
    decoding_.insert(job.id);
    lock.unlock();
    Completion c = decode(job);
    job.bytes = {};
    lock.lock();
    decoding_.erase(job.id);
    if (closed_)
      idleCv_.notify_all();
    else if (cancelled_.erase(job.id) == 0)
      pushLocked(std::move(c));
  }
  // Posted again while jobs are queued: the runner interleaves decodes with other work.
  if (!closed_ && !jobs_.empty())
    runner_.post([self = shared_from_this()] { self->drain(); });
  else
    --tasks_;
}

}  // namespace vegstream::streaming::detail
