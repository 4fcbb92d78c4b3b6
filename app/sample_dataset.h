#pragma once
// The Zion sample as a dataset: `vegstream fly` with no dataset flies over Zion National Park,
// importing ../shared/datasets/zion (SRTM heights + Landsat true colour) once into a dataset
// directory and reusing it afterwards.

#include <filesystem>

#include "core/log.h"
#include "core/result.h"

namespace vegstream::app {

// Imports the sample if `datasetDir` holds no dataset.json yet; returns datasetDir.
Result<std::filesystem::path> ensureZionSample(const std::filesystem::path& samplesDir,
                                               const std::filesystem::path& datasetDir, const Logger& log);

}  // namespace vegstream::app
