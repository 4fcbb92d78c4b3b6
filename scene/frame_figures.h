#pragma once
// The frame's per-frame figures: each stage declares its own (frame_figure.h) in its own file,
// and this is the list of them, in the stages' order — the frame's own figures (pose, totals,
// the recorder, the sun), then streaming, terrain, seeding, trees, simulation and render. From
// the list come frames.csv's columns and rows (playback.h), the summary (flight/summary.h reads
// frames.csv back by the declared names) and the HUD's figures (FigureLookup).
//
// Contract: frameColumns() is frames.csv's header, the contract README.md "Recordings"
// documents; its order is FigureSection's, then the list's, then each stage's declarations'.
// Declaring a figure touches only the stage's file; adding a stage, the stage and this list.

#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "flight/record_table.h"
#include "scene/frame_figure.h"

namespace vegstream::scene {

// Each stage's declarations, appended to `out` (each in its own file, named after the stage).
void declareFrameOwnFigures(FrameFigures& out, const FigureLayout& layout);    // frame_own_figures.cpp
void declareStreamingFigures(FrameFigures& out, const FigureLayout& layout);   // streaming_figures.cpp
void declareTerrainFigures(FrameFigures& out, const FigureLayout& layout);     // terrain_figures.cpp
void declareSeedingFigures(FrameFigures& out, const FigureLayout& layout);     // seeding_figures.cpp
void declareTreeFigures(FrameFigures& out, const FigureLayout& layout);        // tree_figures.cpp
void declareSimulationFigures(FrameFigures& out, const FigureLayout& layout);  // simulation_figures.cpp
void declareRenderFigures(FrameFigures& out, const FigureLayout& layout);      // render_figures.cpp

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
