#pragma once
// A whole dataset loaded at one zoom: every height tile of that zoom mosaicked into one raster
// in Web Mercator pixels, and likewise the imagery. This is the stand-in for the tile streamer
// (issue 5), which will replace it with asynchronous, budgeted loading; until then flights load
// the dataset once, at open, at the finest zoom that fits the caller's limits.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/result.h"
#include "datasets/dataset_format.h"

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

struct ImageryMosaic : MercatorRaster {
  std::vector<uint8_t> rgba;  // sRGB; alpha 0 = no data
};

struct SnapshotLimits {
  uint64_t maxHeightPixels = 350'000;     // the mesh has about two triangles per height pixel
  uint64_t maxImageryPixels = 16'000'000;
  int maxSide = 4096;  // either mosaic's width and height: every Vulkan device takes 4096² textures
};

struct DatasetSnapshot {
  datasets::DatasetMeta meta;
  HeightMosaic heights;
  ImageryMosaic imagery;   // empty (width 0) when the dataset has no imagery
  uint64_t tilesRead = 0;
  uint64_t bytesRead = 0;  // tile files read from disk
};

// Reads dataset.json, picks the finest zoom within the limits for heights and for imagery
// (never finer than the dataset's max zoom) and reads those tiles. The mosaics are cropped to
// the dataset's bounds. Errors name the dataset directory or the tile file.
Result<DatasetSnapshot> loadDatasetSnapshot(const std::filesystem::path& datasetDir, const SnapshotLimits& limits);

}  // namespace vegstream::streaming
