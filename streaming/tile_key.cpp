// Tile keys: names for logs and the file of a tile inside the dataset directory. The paths come
// from datasets/dataset_format (elevationTilePath / imageryTilePath) so that the streamer reads
// exactly what the importers write.

#include "streaming/tile_key.h"

#include <cassert>

namespace vegstream::streaming {

std::string toString(const TileKey& key) {
  std::string s = key.layer == TileLayer::Height ? "height/" : "imagery/";
  s += geo::toString(key.id);
  return s;
}

TileKey parentOf(const TileKey& key) {
  assert(key.id.z > 0);
  return TileKey{key.layer, geo::parent(key.id)};
}

std::string datasetRelativePath(const TileKey& key, const datasets::DatasetMeta& meta) {
  // An empty root makes the dataset_format helpers return the relative path itself.
  const std::filesystem::path root;
  if (key.layer == TileLayer::Height) return datasets::elevationTilePath(root, key.id).generic_string();
  assert(meta.imagery.has_value());  // contract: imagery keys only for datasets that have imagery
  return datasets::imageryTilePath(root, key.id, meta.imagery.value_or(datasets::ImageryFormat::Jpeg)).generic_string();
}

}  // namespace vegstream::streaming
