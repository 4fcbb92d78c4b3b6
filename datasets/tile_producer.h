#pragma once
// One max-zoom tile of a GDAL import (geotiff_import.h): its heights, imagery and NDVI sampled
// from the windows of the sources it needs, de-shaded, encoded and written under the partial
// directory. Thread-safe: every call reads its own windows.

#include <atomic>
#include <filesystem>
#include <optional>
#include <vector>

#include "core/result.h"
#include "datasets/geotiff_import.h"
#include "datasets/imagery_source.h"
#include "datasets/imagery_tiles.h"
#include "datasets/import_journal.h"
#include "datasets/ndvi_source.h"
#include "datasets/source_grid.h"

namespace vegstream::datasets {

struct TileSources {
  const SourceGrid* dem = nullptr;
  const PreparedImagery* imagery = nullptr;  // null: no imagery
  const SourceGrid* imageryGrid = nullptr;
  const ImageryTiling* tiling = nullptr;
  const NdviSource* ndvi = nullptr;          // null: no NDVI layer
  const SourceGrid* landcover = nullptr;     // null: no landcover layer
  HeightResampling resampling = HeightResampling::Bilinear;
};

// A tile's heights (kTileSize², NaN = nodata; heights outside the plausible range are nodata).
Result<std::vector<float>> tileHeights(const TileSources& src, const geo::TileId& id);

// A tile's imagery window and source positions; nullopt where the imagery has none.
Result<std::optional<TileImagery>> tileImagery(const TileSources& src, const geo::TileId& id,
                                               std::optional<ImageryWindow>* keep = nullptr);

// Writes the tile's files under dir; `out` says what was written.
Status produceTile(const std::filesystem::path& dir, const geo::TileId& id, const TileSources& src,
                   const GeoTiffImportOptions& o, TileRecord& out);

}  // namespace vegstream::datasets
