#pragma once
// The frame's per-frame figures: each stage declares its own (frame_figure.h) in its own file
// (frame_stage.h), and this is the list of them, in the stages' order — the frame's own figures
// (pose, totals, the recorder, the sun), then streaming, terrain, seeding, trees, simulation and
// render. From the list come frames.csv's columns and rows (playback.h), the summary
// (flight/summary.h reads frames.csv back by the declared names) and the HUD's figures
// (FigureLookup).
//
// Contract: frameColumns() is frames.csv's header, the contract README.md "Recordings"
// documents; its order is FigureSection's, then the list's, then each stage's declarations'.
// Declaring a figure touches only the stage's file; adding a stage, the stage, this list and the
// list of stages that run (Scene's or the driver's).

#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "flight/record_table.h"
#include "scene/frame_figure.h"

namespace vegstream::scene {

// The frame's own figures (frame_own_figures.cpp): its row, time and pose, cpu_flight_ms,
// cpu_frame_ms, the recorder's times, the sun. Each stage's are its `declareFigures`
// (frame_stage.h).
void declareFrameOwnFigures(FrameFigures& out, const FigureLayout& layout);

// Every stage's figures, in column order.
FrameFigures frameFigures(const FigureLayout& layout);
// frames.csv's columns for a renderer with these passes.
std::vector<flight::RecordColumn> frameColumns(const FigureLayout& layout);

// frames.csv of a recording: one row per record, in order.
flight::RecordTable frameTable(const std::vector<FrameRecord>& records, const FigureLayout& layout);

// The figures by column name, for a reader that picks a few (the HUD).
class FigureLookup {
 public:
  explicit FigureLookup(const FigureLayout& layout);
  // `column` of `record`; NaN where the frame has none. A name no stage declares is a caller's
  // mistake: asserted, and NaN in release builds.
  double operator()(const FrameRecord& record, std::string_view column) const;

 private:
  FrameFigures figures_;
  std::unordered_map<std::string, std::size_t> index_;
};

}  // namespace vegstream::scene
