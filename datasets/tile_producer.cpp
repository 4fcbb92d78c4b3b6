// One max-zoom tile of a GDAL import, from source windows (tile_producer.h).

#include "datasets/tile_producer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "datasets/dataset_finish.h"
#include "datasets/landcover.h"
#include "datasets/tile_codec.h"

namespace vegstream::datasets {
namespace fs = std::filesystem;

Result<std::vector<float>> tileHeights(const TileSources& src, const geo::TileId& id) {
  const auto px = src.dem->tilePixelsToSource(id, kTileSize);
  std::vector<float> heights(px.size(), NAN);
  auto window = src.dem->windowFor(px, 2, kMaxWindowSide);
  if (!window) return window.error();
  if (!*window) return heights;
  Raster& w = **window;
  for (float& v : w.samples)
    if (!(v >= kMinPlausibleHeightM && v <= kMaxPlausibleHeightM)) v = NAN;
  for (size_t i = 0; i < px.size(); ++i)
    heights[i] = src.resampling == HeightResampling::Cubic ? sampleHeightCubic(w, px[i]) : sampleHeight(w, px[i]);
  return heights;
}

Result<std::optional<TileImagery>> tileImagery(const TileSources& src, const geo::TileId& id,
                                               std::optional<ImageryWindow>* keep) {
  TileImagery t;
  t.px = src.imageryGrid->tilePixelsToSource(id, kTileSize);
  auto w = src.imagery->window(*src.imageryGrid, t.px, 1, kMaxWindowSide);
  if (!w) return w.error();
  if (!*w) return std::optional<TileImagery>();
  t.window = (*w)->colour;
  if (keep) *keep = std::move(*w);
  return std::optional<TileImagery>(std::move(t));
}

namespace {

Status writeNdvi(const fs::path& dir, const TileSources& src, const ImageryWindow& w, const TileImagery& t,
                 ColorTile& c, TileRecord& out) {
  auto ndvi = src.ndvi->ndviFor(w, kMaxWindowSide);
  if (!ndvi) return ndvi.error();
  c.ndvi.assign(t.px.size(), 0);
  for (size_t i = 0; i < t.px.size(); ++i) {
    c.ndvi[i] = ndviToByte(sampleValue(*ndvi, t.px[i]));
    out.ndvi = out.ndvi || c.ndvi[i] != 0;
  }
  if (!out.ndvi) return {};
  const fs::path p = ndviTilePath(dir, c.id);
  if (auto s = writeNdviTile(p, c); !s) return s;
  out.bytes += fileBytes(p);
  return {};
}

// The landcover tile: the nearest class at each pixel centre (never blended; decimated windows are
// read nearest too). Written when any pixel has a class.
Status writeLandcover(const fs::path& dir, const geo::TileId& id, const SourceGrid& grid, TileRecord& out) {
  const auto px = grid.tilePixelsToSource(id, kTileSize);
  auto window = grid.windowFor(px, 0, kMaxWindowSide);
  if (!window) return window.error();
  if (!*window) return {};
  if (auto s = checkClassRaster(**window); !s) return s;
  LandcoverTile t;
  t.id = id;
  t.classes.resize(px.size());
  for (size_t i = 0; i < px.size(); ++i) {
    t.classes[i] = nearestClass(**window, px[i]);
    out.landcover = out.landcover || t.classes[i] != 0;
  }
  if (!out.landcover) return {};
  const fs::path p = landcoverTilePath(dir, id);
  if (auto s = writeLandcoverTile(p, t); !s) return s;
  out.bytes += fileBytes(p);
  return {};
}

}  // namespace

Status produceTile(const fs::path& dir, const geo::TileId& id, const TileSources& src, const GeoTiffImportOptions& o,
                   TileRecord& out) {
  HeightTile h;
  h.id = id;
  h.size = kTileSize;
  auto heights = tileHeights(src, id);
  if (!heights) return heights.error();
  h.heights = std::move(*heights);
  out.minH = std::numeric_limits<float>::infinity();
  out.maxH = -std::numeric_limits<float>::infinity();
  for (const float v : h.heights) {
    if (!std::isfinite(v)) continue;
    out.minH = std::min(out.minH, v);
    out.maxH = std::max(out.maxH, v);
    out.elevation = true;
  }
  if (out.elevation) {
    const fs::path p = elevationTilePath(dir, id);
    if (auto s = writeHeightTile(p, h, o.encoding); !s) return s;
    out.bytes += fileBytes(p);
  }
  if (src.landcover)
    if (auto s = writeLandcover(dir, id, *src.landcover, out); !s) return s;
  if (!src.imagery) return {};
  std::optional<ImageryWindow> window;
  auto img = tileImagery(src, id, &window);
  if (!img) return img.error();
  if (!*img) return {};
  ColorTile c;
  c.id = id;
  c.size = kTileSize;
  out.imagery = fillImageryTile(*src.tiling, **img, h.heights, c);
  if (out.imagery) {
    const fs::path p = imageryTilePath(dir, id, o.imageryFormat);
    if (auto s = writeColorTile(p, c, o.imageryFormat, o.jpegQuality); !s) return s;
    out.bytes += fileBytes(p);
  }
  if (!src.ndvi) return {};
  return writeNdvi(dir, src, *window, **img, c, out);
}

}  // namespace vegstream::datasets
