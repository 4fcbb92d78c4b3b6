#pragma once
// dataset.json's "imagery.colour_calibration" ↔ ColourCalibrationRecord (colour_calibration.h):
//   { "method": "levels-chroma-exposure-1", "matrix": [9 numbers, row-major], "offset": [3],
//     "statistics": { "pixels": N, "black": [3], "white": [3], "gains": [3], "grey": [3], "median_chroma": c,
//                     "median_luminance": y, "chroma_gain": k, "exposure": e } }
// Absent or null: identity (datasets written before it). Every number is checked (finite; the
// matrix's and offset's within ±1000); errors name the source and the field.
#include <string>

#include <nlohmann/json.hpp>

#include "core/result.h"
#include "datasets/colour_calibration.h"

namespace vegstream::datasets {

nlohmann::json colourCalibrationJson(const ColourCalibrationRecord& c);
Result<ColourCalibrationRecord> parseColourCalibration(const nlohmann::json& j, const std::string& sourceName);

}  // namespace vegstream::datasets
