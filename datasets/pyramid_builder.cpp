// Lower zooms of a dataset from its finest zoom (pyramid_builder.h). Works from the files on
// disk, one zoom at a time (a zoom needs all of the next finer one), the tiles of one zoom in
// parallel: each parent reads its ≤ 4 children, halves them 2×2 and writes itself.

#include "datasets/pyramid_builder.h"

#include <array>
#include <cassert>
#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "datasets/message.h"
#include "core/parallel_for.h"
#include "datasets/landcover.h"
#include "datasets/tile_codec.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

// Parses a decimal component ("1608", "1608.png" with its extension stripped by the caller).
std::optional<int> parseIndex(const std::string& s) {
  if (s.empty() || s.size() > 9) return std::nullopt;
  int v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
    v = v * 10 + (c - '0');
  }
  return v;
}

// The tiles present at zoom z under root/{z}/{x}/{y}.ext.
std::set<geo::TileId> listTiles(const fs::path& root, int z, const std::string& ext) {
  std::set<geo::TileId> tiles;
  std::error_code ec;
  const fs::path zdir = root / std::to_string(z);
  if (!fs::is_directory(zdir, ec)) return tiles;
  for (const auto& xe : fs::directory_iterator(zdir, ec)) {
    if (!xe.is_directory()) continue;
    const auto x = parseIndex(xe.path().filename().string());
    if (!x) continue;
    for (const auto& ye : fs::directory_iterator(xe.path(), ec)) {
      if (!ye.is_regular_file() || ye.path().extension() != ext) continue;
      const auto y = parseIndex(ye.path().stem().string());
      const geo::TileId id{z, *x, y.value_or(-1)};
      if (y && geo::isValid(id)) tiles.insert(id);
    }
  }
  return tiles;
}

uint64_t fileBytes(const fs::path& p) {
  std::error_code ec;
  const auto n = fs::file_size(p, ec);
  return ec ? 0 : static_cast<uint64_t>(n);
}

// Child pixel block (2·px, 2·py) … +1 of quadrant q for parent pixel (i, j).
struct Quadrant {
  int child;   // index into children(): NW, NE, SW, SE
  int cx, cy;  // top-left child pixel of the 2×2 block
};
Quadrant quadrantOf(int i, int j, int size) {
  const int half = size / 2;
  const int qx = i >= half ? 1 : 0, qy = j >= half ? 1 : 0;
  return {qy * 2 + qx, 2 * (i - qx * half), 2 * (j - qy * half)};
}

// The ≤ 4 children of parentId (NW, NE, SW, SE) that are in `present`, each read by
// read(childId) (a Result); nullopt when none is.
template <class Kid, class Read>
Result<std::optional<std::array<std::optional<Kid>, 4>>> readChildren(const geo::TileId& parentId,
                                                                      const std::set<geo::TileId>& present,
                                                                      Read&& read) {
  std::array<std::optional<Kid>, 4> kids;
  bool any = false;
  const auto ids = geo::children(parentId);
  for (size_t k = 0; k < 4; ++k) {
    if (!present.count(ids[k])) continue;
    auto t = read(ids[k]);
    if (!t) return t.error();
    kids[k] = std::move(*t);
    any = true;
  }
  if (!any) return std::optional<std::array<std::optional<Kid>, 4>>{};
  return std::optional<std::array<std::optional<Kid>, 4>>(std::move(kids));
}

// A child tile read from p must have the dataset's tile size.
template <class Tile>
Result<Tile> checkTileSize(Result<Tile> t, const fs::path& p, const DatasetMeta& meta) {
  if (t && t->size != meta.tileSize)
    return makeError(ErrorKind::InvalidInput,
                     concat("tile ", p, " is ", t->size, " pixels wide; the dataset's tiles are ", meta.tileSize));
  return t;
}

// The 2×2 halving of ≤ 4 child tiles (size × size texels each, NW, NE, SW, SE) into their
// parent: for parent texel `at` (row-major index), add(sum, kid, childTexel) is called on the
// four child texels of its block and returns whether that one was valid (and added to sum);
// where any was, put(at, sum, n) gets the sum of the n valid ones. Returns whether any
// parent texel was put. The "sum" is any accumulator (landcover collects the classes).
template <class Sum, class Kid, class Add, class Put>
bool meanOfValidChildren(const std::array<std::optional<Kid>, 4>& kids, int size, Add&& add, Put&& put) {
  bool valid = false;
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      const Quadrant q = quadrantOf(i, j, size);
      const auto& kid = kids[static_cast<size_t>(q.child)];
      if (!kid) continue;
      Sum sum{};
      int n = 0;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx)
          if (add(sum, *kid,
                  static_cast<size_t>(q.cy + dy) * static_cast<size_t>(size) + static_cast<size_t>(q.cx + dx)))
            ++n;
      if (!n) continue;
      put(static_cast<size_t>(j) * static_cast<size_t>(size) + static_cast<size_t>(i), sum, n);
      valid = true;
    }
  }
  return valid;
}

// The parent tile of the children of parentId in `present` (each read by read(childId)): made
// with its id and size, then blank(tile, texels) sets every texel to "no data", then each texel
// `at` with n valid child texels is put(tile, at, sum, n) (meanOfValidChildren's add and sum).
// nullopt when no child is present, or when no texel was valid and not keepEmpty.
template <class Tile, class Kid, class Sum, class Read, class Blank, class Add, class Put>
Result<std::optional<Tile>> downsample(const geo::TileId& parentId, const std::set<geo::TileId>& present,
                                       const DatasetMeta& meta, bool keepEmpty, Read&& read, Blank&& blank, Add&& add,
                                       Put&& put) {
  auto kids = readChildren<Kid>(parentId, present, read);
  if (!kids) return kids.error();
  if (!*kids) return std::optional<Tile>{};
  const int size = meta.tileSize;
  Tile out;
  out.id = parentId;
  out.size = size;
  blank(out, static_cast<size_t>(size) * static_cast<size_t>(size));
  const bool valid =
      meanOfValidChildren<Sum>(**kids, size, add, [&](size_t at, const Sum& sum, int n) { put(out, at, sum, n); });
  if (!valid && !keepEmpty) return std::optional<Tile>{};
  return std::optional<Tile>(std::move(out));
}

Result<std::optional<HeightTile>> downsampleHeights(const fs::path& dir, const geo::TileId& parentId,
                                                    const std::set<geo::TileId>& present, const DatasetMeta& meta) {
  return downsample<HeightTile, HeightTile, double>(
      parentId, present, meta, false,
      [&](const geo::TileId& id) {
        const fs::path p = elevationTilePath(dir, id);
        return checkTileSize(readHeightTile(p, id, meta.elevationEncoding, meta.tileSize), p, meta);
      },
      [](HeightTile& t, size_t texels) { t.heights.assign(texels, NAN); },
      [](double& sum, const HeightTile& kid, size_t k) {
        const float h = kid.heights[k];
        if (!std::isfinite(h)) return false;
        sum += h;
        return true;
      },
      [](HeightTile& t, size_t at, double sum, int n) { t.heights[at] = static_cast<float>(sum / n); });
}

// Imagery: the mean of the opaque child pixels, opaque; a parent whose children are all
// transparent is kept, transparent.
Result<std::optional<ColorTile>> downsampleColour(const fs::path& dir, const geo::TileId& parentId,
                                                  const std::set<geo::TileId>& present, const DatasetMeta& meta) {
  return downsample<ColorTile, ColorTile, std::array<int, 3>>(
      parentId, present, meta, true,
      [&](const geo::TileId& id) {
        const fs::path p = imageryTilePath(dir, id, *meta.imagery);
        return checkTileSize(readColorTile(p, id, meta.tileSize), p, meta);
      },
      [](ColorTile& t, size_t texels) { t.rgba.assign(texels * 4, 0); },
      [](std::array<int, 3>& sum, const ColorTile& kid, size_t k) {
        const uint8_t* px = &kid.rgba[k * 4];
        if (px[3] == 0) return false;
        for (size_t c = 0; c < 3; ++c) sum[c] += px[c];
        return true;
      },
      [](ColorTile& t, size_t at, const std::array<int, 3>& sum, int n) {
        uint8_t* d = &t.rgba[at * 4];
        for (size_t c = 0; c < 3; ++c) d[c] = static_cast<uint8_t>((sum[c] + n / 2) / n);
        d[3] = 255;
      });
}

// NDVI: the mean of the valid child values (decoded and re-encoded: the mean of the NDVI, not
// of its bytes, though the encoding is linear and the two differ only by rounding).
Result<std::optional<ColorTile>> downsampleNdvi(const fs::path& dir, const geo::TileId& parentId,
                                                const std::set<geo::TileId>& present, const DatasetMeta& meta) {
  return downsample<ColorTile, std::vector<uint8_t>, double>(
      parentId, present, meta, false,
      [&](const geo::TileId& id) { return readNdviTile(ndviTilePath(dir, id), id, meta.tileSize); },
      [](ColorTile& t, size_t texels) { t.ndvi.assign(texels, 0); },
      [](double& sum, const std::vector<uint8_t>& kid, size_t k) {
        const float v = ndviFromByte(kid[k]);
        if (std::isnan(v)) return false;
        sum += v;
        return true;
      },
      [](ColorTile& t, size_t at, double sum, int n) { t.ndvi[at] = ndviToByte(static_cast<float>(sum / n)); });
}

// Landcover: the mode of the valid child classes (landcover.h modeOfClasses: ties to the
// smallest code), never a mean — classes are categories. The "sum" collects the block's classes.
struct ClassBlock {
  std::array<uint8_t, 4> classes{};
  size_t n = 0;
};
Result<std::optional<LandcoverTile>> downsampleLandcover(const fs::path& dir, const geo::TileId& parentId,
                                                         const std::set<geo::TileId>& present,
                                                         const DatasetMeta& meta) {
  return downsample<LandcoverTile, LandcoverTile, ClassBlock>(
      parentId, present, meta, false,
      [&](const geo::TileId& id) { return readLandcoverTile(landcoverTilePath(dir, id), id, meta.tileSize); },
      [](LandcoverTile& t, size_t texels) { t.classes.assign(texels, 0); },
      [](ClassBlock& block, const LandcoverTile& kid, size_t k) {
        if (kid.classes[k] == 0) return false;
        block.classes[block.n++] = kid.classes[k];
        return true;
      },
      [](LandcoverTile& t, size_t at, const ClassBlock& block, int) {
        t.classes[at] = modeOfClasses(std::span(block.classes.data(), block.n));
      });
}

// Each layer's tiles at the zoom being reduced.
struct LayerTiles {
  std::set<geo::TileId> elevation, imagery, ndvi, landcover;
};

// What one parent tile got: the layers written, and their bytes.
struct ParentWrites {
  bool elevation = false, imagery = false, ndvi = false, landcover = false;
  uint64_t bytes = 0;
};

// Writes one layer's parent tile to p when `tile` (what its children made) holds one, with
// write(p, tile): `written` set and its bytes added to `bytes`.
template <class Tile, class Write>
Status writeParentLayer(const Result<std::optional<Tile>>& tile, const fs::path& p, Write&& write, bool& written,
                        uint64_t& bytes) {
  if (!tile) return tile.error();
  if (!*tile) return {};
  if (auto w = write(p, **tile); !w) return w;
  bytes += fileBytes(p);
  written = true;
  return {};
}

// Writes parent tile id of every layer from its children in `tiles` (a layer with no valid child
// gets none).
Status buildParent(const fs::path& dir, const geo::TileId& id, const LayerTiles& tiles, const DatasetMeta& meta,
                   const PyramidOptions& options, ParentWrites& out) {
  auto heights = [&](const fs::path& p, const HeightTile& t) { return writeHeightTile(p, t, meta.elevationEncoding); };
  auto colour = [&](const fs::path& p, const ColorTile& t) {
    return writeColorTile(p, t, *meta.imagery, options.jpegQuality);
  };
  Status s = writeParentLayer(downsampleHeights(dir, id, tiles.elevation, meta), elevationTilePath(dir, id), heights,
                              out.elevation, out.bytes);
  if (s && meta.imagery)
    s = writeParentLayer(downsampleColour(dir, id, tiles.imagery, meta), imageryTilePath(dir, id, *meta.imagery),
                         colour, out.imagery, out.bytes);
  if (s && meta.ndvi)
    s = writeParentLayer(downsampleNdvi(dir, id, tiles.ndvi, meta), ndviTilePath(dir, id), writeNdviTile, out.ndvi,
                         out.bytes);
  if (s && meta.landcover)
    s = writeParentLayer(downsampleLandcover(dir, id, tiles.landcover, meta), landcoverTilePath(dir, id),
                         writeLandcoverTile, out.landcover, out.bytes);
  return s;
}

// The parents written become the tiles of the next zoom down, and are counted in meta.
void keepWritten(const std::vector<geo::TileId>& parents, const std::vector<ParentWrites>& writes, LayerTiles& tiles,
                 DatasetMeta& meta) {
  tiles = {};
  auto keep = [](bool written, const geo::TileId& id, std::set<geo::TileId>& layer, uint64_t& count) {
    if (!written) return;
    layer.insert(id);
    ++count;
  };
  for (size_t i = 0; i < parents.size(); ++i) {
    const ParentWrites& w = writes[i];
    keep(w.elevation, parents[i], tiles.elevation, meta.elevationTiles);
    keep(w.imagery, parents[i], tiles.imagery, meta.imageryTiles);
    keep(w.ndvi, parents[i], tiles.ndvi, meta.ndviTiles);
    keep(w.landcover, parents[i], tiles.landcover, meta.landcoverTiles);
    meta.bytes += w.bytes;
  }
}

}  // namespace

Status buildLowerZooms(const fs::path& dir, DatasetMeta& meta, ProgressSink& progress, const PyramidOptions& options) {
  assert(meta.minZoom >= 0 && meta.minZoom <= meta.maxZoom && meta.tileSize % 2 == 0);
  const std::string imageryExt = meta.imagery == ImageryFormat::Jpeg ? ".jpg" : ".png";
  LayerTiles tiles;
  tiles.elevation = listTiles(dir / "elevation", meta.maxZoom, ".png");
  if (meta.imagery) tiles.imagery = listTiles(dir / "imagery", meta.maxZoom, imageryExt);
  if (meta.ndvi) tiles.ndvi = listTiles(dir / "ndvi", meta.maxZoom, ".png");
  if (meta.landcover) tiles.landcover = listTiles(dir / "landcover", meta.maxZoom, ".png");

  for (int z = meta.maxZoom - 1; z >= meta.minZoom; --z) {
    std::set<geo::TileId> parentSet;
    for (const std::set<geo::TileId>* layer : {&tiles.elevation, &tiles.imagery, &tiles.ndvi, &tiles.landcover})
      for (const auto& t : *layer) parentSet.insert(geo::parent(t));
    const std::vector<geo::TileId> parents(parentSet.begin(), parentSet.end());
    progress.addTotal(parents.size());
    progress.stage(concat("zoom ", z));

    std::vector<ParentWrites> writes(parents.size());
    Status s = parallelFor(parents.size(), options.threads, options.tasks, [&](size_t i) -> Status {
      if (Status b = buildParent(dir, parents[i], tiles, meta, options, writes[i]); !b) return b;
      progress.tileDone(writes[i].bytes);
      return {};
    });
    if (!s) return s;
    keepWritten(parents, writes, tiles, meta);
  }
  return {};
}

}  // namespace vegstream::datasets
