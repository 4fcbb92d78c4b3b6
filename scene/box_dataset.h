#pragma once
// What `vegstream plants` lists from (plants_in_box.h, trees_in_box.h): a dataset opened for a
// lon/lat box, checked once for both — it has imagery (species come from its colour), does not
// cross the antimeridian, and holds the box. Each failure is a user error naming the dataset or
// the box's option.

#include <memory>
#include <string>

#include "core/result.h"
#include "datasets/dataset_format.h"
#include "geo/bounds.h"
#include "streaming/tile_source.h"

namespace vegstream::scene {

struct BoxDataset {
  std::shared_ptr<streaming::TileSource> source;
  datasets::DatasetMeta meta;
};

// `boxName`: how the box is named in messages (the command line's option).
Result<BoxDataset> openBoxDataset(const std::string& dataset, const geo::GeoBounds& box, const std::string& boxName);

}  // namespace vegstream::scene
