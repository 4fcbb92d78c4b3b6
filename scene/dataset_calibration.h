#pragma once
// The dataset's colour calibration (dataset.json's "imagery.colour_calibration",
// datasets/colour_calibration.h) handed to the species choice (vegetation/colour_calibration.h):
// the one place the record becomes the catalog's plain numbers, for the scene, `plants` and `query`.
// A dataset without one (written before it, XYZ imports, the synthetic generator) gets the identity.

#include "datasets/dataset_format.h"
#include "vegetation/species_catalog.h"

namespace vegstream::scene {

vegetation::ColourCalibration colourCalibrationOf(const datasets::DatasetMeta& meta);
// `catalog` with the dataset's calibration.
vegetation::SpeciesCatalog calibratedCatalog(const vegetation::SpeciesCatalog& catalog,
                                             const datasets::DatasetMeta& meta);

}  // namespace vegstream::scene
