#pragma once
// `vegstream generate --out DIR [--lat --lon --size-km --seed …]`: writes a synthetic dataset
// (datasets/synthetic_generator.h) with a progress bar and a one-line summary.

#include "core/log.h"
#include "datasets/synthetic_generator.h"

namespace vegstream::app {

// Exit code: 0; 2 for bad options or an --out that exists and is not empty; 1 for I/O failures.
int runGenerate(const datasets::SyntheticOptions& options, const Logger& log);

}  // namespace vegstream::app
