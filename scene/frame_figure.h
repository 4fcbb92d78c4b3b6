#pragma once
// A per-frame figure as a stage declares it: one column of frames.csv — its name, its unit, its
// decimals, the section it sits in — and how to read it from a frame's record. The stages'
// declarations (frame_figures.h lists them) are the one description of the per-frame figures:
// frames.csv, its column order, the summary (which reads frames.csv back by the names), the HUD
// and the plots all follow them, so a figure is added by adding its declaration.
//
// Contract: `value` reads only the record it is given and returns NaN (flight::kNoValue) where
// the figure does not exist for that frame (an empty cell, never a made-up 0). A stage that adds
// a figure appends it to its section: the columns of the sections before it do not move.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "flight/record_table.h"

namespace vegstream::scene {

struct FrameRecord;

// Where a column sits in frames.csv: the sections in file order; within a section, the stages in
// the list's order (frame_figures.cpp), each stage's figures in its declaration order.
enum class FigureSection {
  Pose,       // the frame, its time and the camera
  CpuStages,  // each CPU stage's time (cpu_frame_ms is their sum)
  CpuFrame,
  GpuFrame,   // the GPU frame and its passes
  Recorder,   // wall time, the recorder's bookkeeping, PNG writing
  GpuCounts,  // the terrain pass's triangles and the pipeline statistics
  Memory,
  Streaming,  // the tile streamer, the terrain's wants and pieces
  Terrain,    // ROAM and the seed triangles, the compute raster
  Plants,     // the classify pass and its culling
  TreeDraws,  // the trees drawn per level
  TreeField,  // the tree tiles placed and paged
  Sun,
};

// What the declarations may depend on besides the record: the renderer's passes, which give the
// gpu_<pass>_ms columns.
struct FigureLayout {
  std::vector<std::string> gpuPasses;  // in column order
  bool perPassMeaningful = false;      // else the gpu_<pass>_ms cells stay empty
};

struct FrameFigure {
  FigureSection section = FigureSection::Pose;
  flight::RecordColumn column;                      // name, decimals, unit
  std::function<double(const FrameRecord&)> value;  // NaN: the figure does not exist this frame
};

using FrameFigures = std::vector<FrameFigure>;

// A count as a cell.
inline double count(uint64_t v) { return static_cast<double>(v); }

}  // namespace vegstream::scene
