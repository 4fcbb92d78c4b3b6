// TileStreamer (tile_streamer.h; README.md has the state diagram). The frame thread owns the
// tile table; the source's threads and the decode threads only talk to it through the
// DecodePipeline's completion queue, which update() drains. So no tile state is ever touched by
// two threads, and update() never waits for more than that queue's mutex.

#include "streaming/tile_streamer.h"

#include <chrono>
#include <utility>

#include "streaming/paired_fetch.h"
#include "streaming/tile_streamer_impl.h"

namespace vegstream::streaming {

const char* toString(TileState s) {
  switch (s) {
    case TileState::Unloaded: return "unloaded";
    case TileState::Requested: return "requested";
    case TileState::Decoding: return "decoding";
    case TileState::ResidentCpu: return "resident-cpu";
    case TileState::Uploading: return "uploading";
    case TileState::ResidentGpu: return "resident-gpu";
    case TileState::FailedTemporarily: return "failed-temporarily";
    case TileState::Failed: return "failed";
  }
  return "?";
}

TileStreamer::TileStreamer(std::shared_ptr<TileSource> source, datasets::DatasetMeta meta, StreamingOptions options,
                           Logger log)
    : impl_(std::make_unique<Impl>(std::move(source), std::move(meta), options, std::move(log))) {}

TileStreamer::~TileStreamer() {
  // Stop listening first (later callbacks and tasks find the pipeline closed), then free the source.
  impl_->pipeline->stop();
  for (const auto& [id, key] : impl_->active)
    if (impl_->table[key].state == TileState::Requested) {
      impl_->source->cancel(id);
      if (key.layer == TileLayer::Imagery) detail::cancelCompanions(*impl_->source, impl_->meta, id);
    }
}

const datasets::DatasetMeta& TileStreamer::meta() const { return impl_->meta; }
const StreamingOptions& TileStreamer::options() const { return impl_->options; }
const StreamingFrameStats& TileStreamer::frameStats() const { return impl_->stats; }

bool TileStreamer::waitForArrivals(std::chrono::milliseconds timeout) {
  return impl_->pipeline->waitForCompletions(timeout);
}
TileStreamer::IoProgress TileStreamer::ioProgress() const {
  return {impl_->source->inFlight(), impl_->source->counters(), impl_->pipeline->decodesQueued()};
}
uint32_t TileStreamer::gpuSlotCount() const { return impl_->slots.count(); }

void TileStreamer::update(std::span<const TileWant> wants, double timeS) {
  Impl& m = *impl_;
  ++m.frame;
  m.stats = {};
  m.takeWants(wants, timeS);
  m.cancelUnwanted();  // before taking completions: a cancelled tile never becomes resident
  m.takeCompletions(timeS);
  m.schedule(timeS);
  m.finishStats(timeS);
}

std::shared_ptr<const ResidentTile> TileStreamer::get(const TileKey& key) {
  auto it = impl_->table.find(key);
  if (it == impl_->table.end() || !isResident(it->second.state)) return nullptr;
  it->second.lastUsedFrame = impl_->frame;
  return it->second.tile;
}

ResidentLookup TileStreamer::findResident(const TileKey& key) {
  auto [e, up] = impl_->nearest(key, isResident);
  if (!e) return {};
  e->lastUsedFrame = impl_->frame;
  return {e->tile, up};
}

TileStreamer::GpuLookup TileStreamer::findGpuResident(const TileKey& key) {
  auto [e, up] = impl_->nearest(key, [](TileState s) { return s == TileState::ResidentGpu; });
  if (!e) return {};
  e->lastUsedFrame = impl_->frame;
  return {e->tile, e->slot, up};
}

std::optional<TileStreamer::Failure> TileStreamer::failure(const TileKey& key) const {
  auto it = impl_->table.find(key);
  if (it == impl_->table.end()) return std::nullopt;
  const TileState s = it->second.state;
  return s == TileState::Failed || s == TileState::FailedTemporarily ? it->second.failure : std::nullopt;
}

TileState TileStreamer::state(const TileKey& key) const {
  auto it = impl_->table.find(key);
  return it == impl_->table.end() ? TileState::Unloaded : it->second.state;
}

std::vector<TileKey> TileStreamer::takeResidencyChanges() { return std::exchange(impl_->residencyChanges, {}); }

}  // namespace vegstream::streaming
