// The list of the stages' figure declarations and what is made from it (frame_figures.h).

#include "scene/frame_figures.h"

#include <algorithm>
#include <cassert>

#include "scene/frame_driver.h"
#include "scene/render_stage.h"
#include "scene/seeding_stage.h"
#include "scene/simulation_stage.h"
#include "scene/streaming_stage.h"
#include "scene/terrain_stage.h"
#include "scene/tree_stage.h"

namespace vegstream::scene {

FrameFigures frameFigures(const FigureLayout& layout) {
  FrameFigures figures;
  for (auto declare : {declareFrameOwnFigures, StreamingStage::declareFigures, TerrainStage::declareFigures,
                       SeedingStage::declareFigures, TreeStage::declareFigures, SimulationStage::declareFigures,
                       RenderStage::declareFigures})
    declare(figures, layout);
  std::stable_sort(figures.begin(), figures.end(),
                   [](const FrameFigure& a, const FrameFigure& b) { return a.section < b.section; });
  return figures;
}

std::vector<flight::RecordColumn> frameColumns(const FigureLayout& layout) {
  std::vector<flight::RecordColumn> columns;
  for (const FrameFigure& f : frameFigures(layout)) columns.push_back(f.column);
  return columns;
}

flight::RecordTable frameTable(const std::vector<FrameRecord>& records, const FigureLayout& layout) {
  const FrameFigures figures = frameFigures(layout);
  std::vector<flight::RecordColumn> columns;
  for (const FrameFigure& f : figures) columns.push_back(f.column);
  flight::RecordTable table(std::move(columns));
  for (const FrameRecord& record : records) {
    std::vector<double>& row = table.addRow();
    for (std::size_t c = 0; c < figures.size(); ++c) row[c] = figures[c].value(record);
  }
  return table;
}

FigureLookup::FigureLookup(const FigureLayout& layout) : figures_(frameFigures(layout)) {
  for (std::size_t i = 0; i < figures_.size(); ++i) index_.emplace(figures_[i].column.name, i);
}

double FigureLookup::operator()(const FrameRecord& record, std::string_view column) const {
  const auto it = index_.find(std::string(column));
  assert(it != index_.end() && "a column no stage declares");
  return it == index_.end() ? flight::kNoValue : figures_[it->second].value(record);
}

}  // namespace vegstream::scene
