#pragma once
// Which tile: a layer of the dataset (heights or imagery) and an XYZ tile id.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "datasets/dataset_format.h"
#include "geo/xyz_tiles.h"

namespace vegstream::streaming {

enum class TileLayer : uint8_t { Height = 0, Imagery = 1 };

struct TileKey {
  TileLayer layer = TileLayer::Height;
  geo::TileId id;

  auto operator<=>(const TileKey&) const = default;
};

// "height/12/758/1608", "imagery/12/758/1608": log lines and error messages.
std::string toString(const TileKey& key);

// The parent one zoom up (contract: key.id.z > 0).
TileKey parentOf(const TileKey& key);

// The file of the tile inside the dataset, '/'-separated: "elevation/12/758/1608.png",
// "imagery/12/758/1608.jpg" (extension from the dataset's imagery format).
std::string datasetRelativePath(const TileKey& key, const datasets::DatasetMeta& meta);

struct TileKeyHash {
  std::size_t operator()(const TileKey& k) const noexcept {
    const uint64_t v = (uint64_t(k.layer) << 62) ^ (uint64_t(uint32_t(k.id.z)) << 56) ^
                       (uint64_t(uint32_t(k.id.x)) << 28) ^ uint64_t(uint32_t(k.id.y));
    return std::hash<uint64_t>{}(v);
  }
};

}  // namespace vegstream::streaming
