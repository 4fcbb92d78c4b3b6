// Shared last steps of writing a dataset (dataset_finish.h).

#include "datasets/dataset_finish.h"

#include <cassert>
#include <set>
#include <system_error>

#include "datasets/pyramid_builder.h"
#include "datasets/tilejson.h"

namespace vegstream::datasets {
namespace fs = std::filesystem;

int singleTileZoom(const std::vector<geo::TileId>& tiles) {
  assert(!tiles.empty());
  std::set<geo::TileId> level(tiles.begin(), tiles.end());
  int z = tiles.front().z;
  while (level.size() > 1 && z > 0) {
    std::set<geo::TileId> up;
    for (const auto& t : level) up.insert(geo::parent(t));
    level = std::move(up);
    --z;
  }
  return z;
}

uint64_t fileBytes(const fs::path& path) {
  std::error_code ec;
  const auto n = fs::file_size(path, ec);
  return ec ? 0 : static_cast<uint64_t>(n);
}

Result<DatasetMeta> finishDataset(const fs::path& dir, DatasetMeta meta, ProgressSink& progress, int threads,
                                  int jpegQuality, TaskRunner* tasks) {
  if (meta.minZoom < meta.maxZoom) {
    PyramidOptions po;
    po.threads = threads;
    po.tasks = tasks;
    po.jpegQuality = jpegQuality;
    progress.stage("lower zooms");
    if (auto s = buildLowerZooms(dir, meta, progress, po); !s) return s.error();
  }
  // The TileJSON files first: dataset.json stays the last file a finished dataset gets.
  if (auto s = writeTileJsons(dir, meta); !s) return s.error();
  if (auto s = writeDatasetMeta(dir, meta); !s) return s.error();
  return meta;
}

std::string defaultDatasetName(const fs::path& out) {
  fs::path p = out.lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  std::string name = p.filename().string();
  return name.empty() || name == "." || name == ".." ? std::string("dataset") : name;
}

}  // namespace vegstream::datasets
