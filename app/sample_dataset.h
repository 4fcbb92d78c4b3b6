#pragma once
// The default datasets of `fly`, `record` and `snapshot` when no DATASET is given: the Zion
// sample (SRTM heights + Landsat true colour from ../shared/datasets/zion) imported once into a
// dataset directory and reused afterwards. Where the sample is missing (a clone without
// ../shared), `fly` flies over the synthetic dataset instead (what `vegstream generate` makes),
// generated once into out/datasets/synthetic and reused; it says so in one log line.
//
// The samples directory is compiled in (VEGSTREAM_DATASETS_DIR, ../shared/datasets);
// the environment variable VEGSTREAM_SAMPLES_DIR replaces it (tests point it at a missing
// directory).

#include <filesystem>
#include <string>

#include "core/log.h"
#include "core/result.h"

namespace vegstream::app {

// $VEGSTREAM_SAMPLES_DIR when set and not empty, else `compiledIn`.
std::string samplesDirFromEnvironment(const std::string& compiledIn);

// Imports the sample if `datasetDir` holds no dataset.json yet; returns datasetDir.
Result<std::filesystem::path> ensureZionSample(const std::filesystem::path& samplesDir,
                                               const std::filesystem::path& datasetDir, const Logger& log);

// The Zion sample as ensureZionSample makes it when the sample (or an earlier import of it) is
// there; else the synthetic dataset, generated into `syntheticDir` when it holds no dataset.json
// yet. Either way of falling back logs one line.
Result<std::filesystem::path> ensureDefaultDataset(const std::filesystem::path& samplesDir,
                                                   const std::filesystem::path& zionDir,
                                                   const std::filesystem::path& syntheticDir, const Logger& log);

}  // namespace vegstream::app
