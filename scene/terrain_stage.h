#pragma once
// The terrain stage (frame_stage.h): the streamed terrain's pieces for the frame's time — ROAM
// updated over what is resident, each piece with its heights and imagery (parents standing in)
// — as the renderer's terrain draws (FrameRequest::terrain). Its selection ran in the streaming
// stage (the wants), timed as the terrain's. Figures: cpu_terrain_ms, the pieces, ROAM and the
// seed triangles (terrain::TerrainFrameFigures).

#include <vector>

#include "render/frame_types.h"
#include "scene/frame_figure.h"
#include "scene/frame_stage.h"
#include "terrain/streamed_terrain.h"

namespace vegstream::scene {

class TerrainStage final : public FrameStage {
 public:
  explicit TerrainStage(terrain::StreamedTerrain& terrain) : terrain_(terrain) {}
  void run(FrameContext& context) override;
  static void declareFigures(FrameFigures& out, const FigureLayout& layout);

 private:
  terrain::StreamedTerrain& terrain_;
  std::vector<render::TerrainDraw> draws_;  // what the request points at
};

}  // namespace vegstream::scene
