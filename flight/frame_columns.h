#pragma once
// The columns of frames.csv, in file order, for a renderer with the given GPU passes: the
// contract other tools read (README.md "Recordings" documents every column). Filling a row is
// the frame driver's (scene/frame_table.h); this is the plain list, so reports, summaries and
// tests read it without the renderer.

#include <string>
#include <vector>

#include "flight/record_table.h"

namespace vegstream::flight {

// The columns of frames.csv for a renderer with these passes, in file order.
std::vector<RecordColumn> frameColumns(const std::vector<std::string>& gpuPasses);

// "gpu_terrain_ms" for pass "terrain" (lower case; anything but a-z0-9 becomes '_').
std::string gpuPassColumn(const std::string& pass);

}  // namespace vegstream::flight
