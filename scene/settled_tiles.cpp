// Settled tile reads through the streamer (settled_tiles.h).

#include "scene/settled_tiles.h"

#include <spdlog/logger.h>

namespace vegstream::scene {

SettledTiles::SettledTiles(std::shared_ptr<streaming::TileSource> source, datasets::DatasetMeta meta)
    : warnings_(std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(16)) {
  // The streamer says why a tile failed only in its log: warnings land here, not on stderr.
  auto log = std::make_shared<spdlog::logger>("settled-tiles", warnings_);
  log->set_pattern("%v");
  log->set_level(spdlog::level::warn);
  streamer_ = std::make_unique<streaming::TileStreamer>(std::move(source), std::move(meta),
                                                        streaming::StreamingOptions{}, std::move(log));
}

SettledTiles::~SettledTiles() = default;

void SettledTiles::settle(const std::vector<streaming::TileKey>& keys) {
  std::vector<streaming::TileWant> wants;
  for (const streaming::TileKey& k : keys)
    if (!known_.count(k)) wants.push_back({k, 1.0, false});
  if (wants.empty()) return;
  // Each settle is a later "frame": a tile that failed for now may be asked again after the back-off.
  timeS_ += streamer_->settle(wants, timeS_) + 1.0;
  for (const streaming::TileWant& w : wants) {
    std::shared_ptr<const streaming::ResidentTile> tile = streamer_->get(w.key);
    const streaming::TileState state = streamer_->state(w.key);
    if (!tile && state != streaming::TileState::Failed && !error_)
      error_ = makeError(ErrorKind::Io, "tile " + toString(w.key) + " could not be read (" + toString(state) + ")");
    known_.emplace(w.key, std::move(tile));  // null: the dataset has no tile there (or it failed)
  }
  // A tile that failed — rather than one that does not exist — was logged as a warning.
  const std::vector<std::string> logged = warnings_->last_formatted();
  if (!logged.empty() && !error_) {
    std::string message = logged.front();
    while (!message.empty() && (message.back() == '\n' || message.back() == '\r')) message.pop_back();
    const bool corrupt = message.find("cannot be decoded") != std::string::npos;
    error_ = makeError(corrupt ? ErrorKind::InvalidInput : ErrorKind::Io, message);
  }
}

void SettledTiles::prefetch(const std::vector<streaming::TileKey>& keys) { settle(keys); }

const streaming::ResidentTile* SettledTiles::finest(streaming::TileKey key) {
  const int minZoom = streamer_->meta().minZoom;
  for (streaming::TileKey a = key; a.id.z >= minZoom; a = streaming::parentOf(a)) {
    settle({a});
    if (const auto& tile = known_.at(a)) return tile.get();
    if (a.id.z == 0) break;
  }
  return nullptr;
}

}  // namespace vegstream::scene
