#pragma once
// Tiles read through the streamer the frame uses (streaming/tile_streamer.h), for tools that
// want whole areas at full detail rather than what a camera sees: every tile is asked for and
// waited on (TileStreamer::settle), then kept, so what they read is exactly what a settled flight
// reads. `finest(key)` answers as a flight's ResidentHeights lookup does once everything near is
// resident: the key's own tile when the dataset has it, else its nearest ancestor that exists.
//
// A tile that exists but cannot be fetched or decoded is not silently replaced by its parent: it
// becomes error(), with the decoder's or the source's message naming the tile
// (TileStreamer::failure).

#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "core/result.h"
#include "streaming/tile_streamer.h"

namespace vegstream::scene {

class SettledTiles {
 public:
  SettledTiles(std::shared_ptr<streaming::TileSource> source, datasets::DatasetMeta meta);
  ~SettledTiles();

  // Asks for every key at once (one settle: the decodes run in parallel on the workers).
  void prefetch(const std::vector<streaming::TileKey>& keys);

  // The finest tile at or above `key`, down to the dataset's min zoom, that the dataset has;
  // null when none has. Valid as long as this object.
  const streaming::ResidentTile* finest(streaming::TileKey key);

  // The first tile that exists but could not be read (then results may miss ground).
  const std::optional<Error>& error() const { return error_; }

 private:
  void settle(const std::vector<streaming::TileKey>& keys);

  std::unique_ptr<streaming::TileStreamer> streamer_;
  std::map<streaming::TileKey, std::shared_ptr<const streaming::ResidentTile>> known_;  // null: none there
  std::optional<Error> error_;
  double timeS_ = 0.0;
};

}  // namespace vegstream::scene
