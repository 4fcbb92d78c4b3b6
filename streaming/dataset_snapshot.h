#pragma once
// A dataset's heights at one zoom, mosaicked into one raster in Web Mercator pixels: the ground
// model a flight resolves terrain-relative altitudes against (the same for every frame and every
// streaming state, so recordings stay deterministic).

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/log.h"
#include "core/result.h"
#include "datasets/dataset_format.h"
#include "streaming/tile_source.h"

namespace vegstream::streaming {

// A raster on the Web Mercator grid of zoom `zoom`: pixel (col, row) has its centre at
// EPSG:3857 metres (x0 + col·pixelM, y0 − row·pixelM), rows from the north.
struct MercatorRaster {
  int zoom = 0;
  int width = 0;
  int height = 0;
  double x0 = 0.0;
  double y0 = 0.0;
  double pixelM = 0.0;
};

struct HeightMosaic : MercatorRaster {
  std::vector<float> heights;  // NaN = nodata
};

// The ceiling of the ground mosaics (checked before allocating: 4 bytes a height pixel, 6 an
// imagery pixel). A dataset whose coarsest zoom already exceeds it is refused.
struct SnapshotLimits {
  uint64_t maxHeightPixels = 1'000'000;
  int maxSide = 4096;
  long deadlineMs = 60'000;  // each layer's tiles, fetched as one batch (ground_fetch.h)
  Logger log;                // the warning about tiles that failed; null: none
};

// Heights of a whole dataset at one zoom, read through a tile source: the finest zoom within
// the limits (never finer than the dataset's max zoom), cropped to the dataset's bounds. A tile
// the source does not have is nodata. Blocking: for what must be known before a flight starts —
// the ground under scripted paths (terrain-relative altitudes) — never on the frame path. The
// tiles are fetched at once, like the streamer's (retries, per-request deadlines, caps), within
// limits.deadlineMs; a tile that still fails, or does not decode as a tile of the dataset's size,
// is nodata too, with one warning (limits.log) for all of them: only when every tile fails is it
// an error (InvalidInput, the first failure, naming the file or URL).
Result<HeightMosaic> loadGroundHeights(TileSource& source, const datasets::DatasetMeta& meta,
                                       const SnapshotLimits& limits);

// The imagery (and NDVI) over the same pixels: what the trees read their species from (issue 20,
// scene/tree_ground.h).
struct ImageryMosaic : MercatorRaster {
  std::vector<uint8_t> rgba;  // width × height × 4, sRGB as in the tiles, alpha 0 = no imagery
  // width × height bytes in datasets::ndviToByte's encoding, 0 = no NDVI there; empty when the
  // dataset has no NDVI layer.
  std::vector<uint8_t> ndvi;
  // width × height landcover class codes (datasets/landcover.h, the tiles of the same zoom: the
  // mode pyramid's classes, never blended), 0 = no class there; empty when the dataset has no
  // landcover layer.
  std::vector<uint8_t> landcover;
};

// The dataset's imagery tiles of `grid.zoom` mosaicked on `grid` (a loadGroundHeights result, or
// its MercatorRaster part): pixel for pixel the same Web Mercator pixels. A missing imagery tile
// is transparent, a missing NDVI tile 0 (no NDVI). Blocking, and failed tiles are handled, like
// loadGroundHeights'. Errors: InvalidInput for a dataset without imagery, or when every tile of a
// layer failed (the first failure, named).
// The landcover tile `id`'s class codes (size × size, datasets/landcover.h), empty where the
// source has no such tile. Errors: a corrupt tile (InvalidInput, named), Io from the source.
Result<std::vector<uint8_t>> loadLandcoverClasses(TileSource& source, const geo::TileId& id, int size);

Result<ImageryMosaic> loadGroundImagery(TileSource& source, const datasets::DatasetMeta& meta,
                                        const MercatorRaster& grid, const SnapshotLimits& limits = {});

}  // namespace vegstream::streaming
