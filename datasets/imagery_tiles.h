#pragma once
// One max-zoom imagery tile as the GeoTIFF importer writes it (geotiff_import.cpp): the prepared
// imagery (imagery_source.h) sampled bilinearly at the tile's pixel centres, de-shaded with the
// tile's own heights under the acquisition sun (deshading.h), and sRGB-encoded into bytes
// (srgb.h); and the samples the sun is estimated from when its time is unknown (sun_estimate.h).
// Everything is per tile, so memory stays bounded by the tile size.

#include <functional>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "datasets/deshading.h"
#include "datasets/source_grid.h"
#include "datasets/sun_estimate.h"
#include "datasets/tile_codec.h"
#include "geo/xyz_tiles.h"

namespace vegstream::datasets {

struct ImageryTiling {
  bool linear = false;               // PreparedImagery::linear: linear 0 … 1, else sRGB-encoded 0 … 255
  std::optional<glm::dvec3> sun;     // de-shade under this sun (unit, ENU); nullopt: not de-shaded
  double directFraction = kDirectFraction;
};

// A max-zoom tile's imagery: the prepared imagery's window around it (3 channels, NaN = no
// data) and the whole-raster source positions of the tile's pixel centres
// (SourceGrid::tilePixelsToSource).
struct TileImagery {
  Raster window;
  std::vector<glm::dvec2> px;
};

// Fills c.rgba (size² × 4, alpha 255 where there is colour) from `img`. heights: the tile's
// (size², NaN = nodata), for the normals when de-shading. Returns whether any pixel has colour.
bool fillImageryTile(const ImageryTiling& tiling, const TileImagery& img, const std::vector<float>& heights,
                     ColorTile& c);

// Samples for estimateSun (normal, log luminance, one group per 64 × 64-pixel block) from up to
// 64 of `tiles` spread evenly over the list, thinned to at most maxSamples. heightsOf(tile)
// gives a tile's heights (size², as above), imageryOf(tile) its imagery (nullopt: none there).
std::vector<ShadingSample> collectShadingSamples(
    const ImageryTiling& tiling, const std::vector<geo::TileId>& tiles, int size,
    const std::function<std::vector<float>(const geo::TileId&)>& heightsOf,
    const std::function<std::optional<TileImagery>(const geo::TileId&)>& imageryOf, size_t maxSamples = 60000);

}  // namespace vegstream::datasets
