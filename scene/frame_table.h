#pragma once
// Frame records → the rows of frames.csv (flight/frame_columns.h names the columns, README.md
// "Recordings" says what each means). An empty cell (NaN) means the figure does not exist.

#include <string>
#include <vector>

#include "flight/record_table.h"
#include "scene/frame_driver.h"

namespace vegstream::scene {

struct FrameTableLayout {
  std::vector<std::string> gpuPasses;  // the renderer's passes, in column order
  bool perPassMeaningful = false;      // else the gpu_<pass>_ms cells stay empty
};

// One row per record, frame index = position; recorderMs[i] is the bookkeeping the caller spent
// on record i (recorder_ms), pngMs[i] the PNG writing (NaN: not saved).
flight::RecordTable frameTable(const std::vector<FrameRecord>& records, const std::vector<double>& wallMs,
                               const std::vector<double>& recorderMs, const std::vector<double>& pngMs,
                               const FrameTableLayout& layout);

}  // namespace vegstream::scene
