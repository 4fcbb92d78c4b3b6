#pragma once
// One source tile (xyz_source.h) read and decoded for the dataset: 256-pixel tiles as they are;
// a 512-pixel tile at zoom z split exactly into the four 256-pixel tiles of zoom z + 1 that
// cover it (pixel blocks [256·i, 256·i + 256) × [256·j, 256·j + 256) → tile (2x + i, 2y + j)),
// with no resampling, so the dataset keeps 256-pixel tiles (dataset_format.h's kTileSize, which
// the pyramid builder, the streamer and the terrain assume).

#include <optional>
#include <vector>

#include "core/result.h"
#include "datasets/tile_codec.h"
#include "datasets/xyz_source.h"

namespace vegstream::datasets {

inline constexpr int kLargeSourceTileSize = 512;

// Empty: the source has no tile there. Errors name the tile (its path or URL): undecodable,
// or neither 256 nor 512 pixels wide (Unsupported).
Result<std::vector<HeightTile>> readSourceHeightTiles(XyzSource& source, const geo::TileId& id,
                                                      ElevationEncoding encoding);
Result<std::vector<ColorTile>> readSourceColorTiles(XyzSource& source, const geo::TileId& id);

// The pixel size (256 or 512) of the first tile of `ids` (in order) that the source has;
// nullopt when it has none of them.
Result<std::optional<int>> probeSourceTileSize(XyzSource& source, const std::vector<geo::TileId>& ids);

// The four 256-pixel tiles of a 512-pixel tile (children in geo::children order).
std::vector<HeightTile> splitHeightTile(const HeightTile& tile);
std::vector<ColorTile> splitColorTile(const ColorTile& tile);

}  // namespace vegstream::datasets
