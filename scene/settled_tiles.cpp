// Settled tile reads through the streamer (settled_tiles.h).

#include "scene/settled_tiles.h"

namespace vegstream::scene {

SettledTiles::SettledTiles(std::shared_ptr<streaming::TileSource> source, datasets::DatasetMeta meta)
    : streamer_(std::make_unique<streaming::TileStreamer>(std::move(source), std::move(meta),
                                                          streaming::StreamingOptions{}, makeNullLogger())) {}

SettledTiles::~SettledTiles() = default;

void SettledTiles::settle(const std::vector<streaming::TileKey>& keys) {
  std::vector<streaming::TileWant> wants;
  for (const streaming::TileKey& k : keys)
    if (!known_.count(k)) wants.push_back({k, 1.0, false});
  if (wants.empty()) return;
  // Each settle is a later "frame", one back-off later in the streamer's time (never the wall
  // clock's: the result depends on the data alone): a tile that failed for now is asked again.
  streamer_->settle(wants, timeS_);
  timeS_ += streamer_->options().failedRetryAfterS;
  for (const streaming::TileWant& w : wants) {
    std::shared_ptr<const streaming::ResidentTile> tile = streamer_->get(w.key);
    if (!tile && !error_) {
      // A tile the dataset lacks is Failed without a failure: its parent answers for it.
      if (const auto failure = streamer_->failure(w.key))
        error_ =
            makeError(failure->undecodable ? ErrorKind::InvalidInput : ErrorKind::Io,
                      "tile " + toString(w.key) +
                          (failure->undecodable ? " cannot be decoded: " : " could not be read: ") + failure->message);
      else if (streamer_->state(w.key) != streaming::TileState::Failed)
        error_ = makeError(ErrorKind::Io, "tile " + toString(w.key) + " could not be read (" +
                                              toString(streamer_->state(w.key)) + ")");
    }
    known_.emplace(w.key, std::move(tile));  // null: the dataset has no tile there (or it failed)
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
