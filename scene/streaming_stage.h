#pragma once
// The streaming stage (frame_stage.h): the tiles the terrain wants for the frame's views and the
// look-ahead views, asked of the tile streamer — realtime: one update, never waiting; settled:
// settle rounds until the wants stop changing, the wait measured apart — then the imagery
// uploads this frame records (FrameRequest::imageryUploads, pointing into the resident tiles).
// Figures: cpu_streaming_ms, streaming_wait_ms, the streamer's frame, cpu_bytes.

#include <cstdint>
#include <vector>

#include "scene/frame_figure.h"
#include "scene/frame_stage.h"
#include "streaming/tile_streamer.h"
#include "terrain/streamed_terrain.h"

namespace vegstream::scene {

class StreamingStage final : public FrameStage {
 public:
  // `groundBytes`: the ground mosaic, counted in cpu_bytes.
  StreamingStage(streaming::TileStreamer& streamer, terrain::StreamedTerrain& terrain, bool settled,
                 uint64_t groundBytes);
  void run(FrameContext& context) override;
  static void declareFigures(FrameFigures& out, const FigureLayout& layout);

 private:
  streaming::StreamingFrameStats settle(std::vector<streaming::TileWant>& wants, double timeS);
  void planUploads();

  streaming::TileStreamer& streamer_;
  terrain::StreamedTerrain& terrain_;
  bool settled_;
  uint64_t groundBytes_;
  std::vector<streaming::Upload> planned_;
  std::vector<render::ImageryUpload> uploads_;  // what the request points at
};

}  // namespace vegstream::scene
