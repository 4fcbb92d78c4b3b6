// The dataset's colour calibration as the catalog's numbers (dataset_calibration.h).
#include "scene/dataset_calibration.h"

namespace vegstream::scene {

vegetation::ColourCalibration colourCalibrationOf(const datasets::DatasetMeta& meta) {
  vegetation::ColourCalibration out;
  if (!meta.colourCalibration) return out;
  const auto& c = *meta.colourCalibration;
  for (size_t r = 0; r < 3; ++r)
    out.rows[r] = glm::vec4(static_cast<float>(c.matrix[r * 3]), static_cast<float>(c.matrix[r * 3 + 1]),
                            static_cast<float>(c.matrix[r * 3 + 2]), static_cast<float>(c.offset[r]));
  return out;
}

vegetation::SpeciesCatalog calibratedCatalog(const vegetation::SpeciesCatalog& catalog,
                                             const datasets::DatasetMeta& meta) {
  vegetation::SpeciesCatalog out = catalog;
  out.calibration = colourCalibrationOf(meta);
  return out;
}

}  // namespace vegstream::scene
