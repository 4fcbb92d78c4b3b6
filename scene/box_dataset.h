#pragma once
// What `vegstream plants` lists from (plants_in_box.h, trees_in_box.h): a dataset opened for a
// lon/lat box, checked once for both — it has imagery (species come from its colour), does not
// cross the antimeridian, and holds the box. Each failure is a user error naming the dataset or
// the box's option. The species catalog comes with it under the dataset's colour calibration.

#include <memory>
#include <string>

#include "core/result.h"
#include "datasets/dataset_format.h"
#include "geo/bounds.h"
#include "geo/local_frame.h"
#include "streaming/tile_source.h"
#include "vegetation/species_catalog.h"

namespace vegstream::scene {

struct BoxDataset {
  std::shared_ptr<streaming::TileSource> source;
  datasets::DatasetMeta meta;
  vegetation::SpeciesCatalog catalog;  // the given one with the imagery's calibration (dataset_calibration.h)
  // The flight's frame (scene.cpp: ENU at the centre of the dataset's bounds): positions in it are
  // those a flight computes, bit for bit, not merely at the same lat/lon.
  geo::LocalFrame frame;
};

// `boxName`: how the box is named in messages (the command line's option).
Result<BoxDataset> openBoxDataset(const std::string& dataset, const geo::GeoBounds& box, const std::string& boxName,
                                  const vegetation::SpeciesCatalog& catalog);

}  // namespace vegstream::scene
