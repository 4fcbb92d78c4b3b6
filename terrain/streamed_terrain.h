#pragma once
// The terrain over streamed tiles: each frame it says which tiles it wants (the chunked-LOD
// selection of tile_selection.h for the camera, plus prefetches for the poses expected in the
// next seconds), and after the streamer's update it tessellates whatever is resident with ROAM
// (roam_tessellator.h) and hands out the drawable pieces: one per selected tile, coloured from
// the nearest resident imagery — the tile's own or an ancestor's, never a hole — plus the seed
// triangles the vegetation grows on.
//
// The selection decides what data is streamed (a tile is wanted where its heights and imagery
// are fine enough for the error bound); ROAM decides the triangles over the data that is there:
// every vertex is sampled from the finest resident height tile and morphs to new heights when
// finer tiles arrive or a split creates it (RoamMesh); a finer imagery tile fades in over the
// layer drawn before, over `fadeS` seconds of flight time. When the wanted tiles do not fit the
// CPU or GPU budget, the selection's error bound relaxes (×1.5 per frame) until they do, and
// recovers slowly when there is room again; figures() says by how much.
//
// The streamer must be made with StreamingOptions::heightExtra = wedgieTableBuilder(minZoom)
// (streamingOptionsFor does it): ROAM reads its error bounds from the tables.
//
// Frame thread only. Deterministic for a deterministic streamer (settled recordings).

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "geo/local_frame.h"
#include "streaming/tile_streamer.h"
#include "terrain/eye_space.h"
#include "terrain/resident_heights.h"
#include "terrain/roam_tessellator.h"
#include "terrain/terrain_mesh.h"
#include "terrain/tile_selection.h"

namespace vegstream::terrain {

struct StreamedTerrainOptions {
  double maxErrorPx = 2.0;          // screen-space error bound (the selection's relaxes under budget pressure)
  int maxNodes = 384;               // most pieces drawn
  double fadeS = 0.5;               // morph / imagery fade-in time, seconds of flight
  double lookAheadPriority = 0.25;  // look-ahead wants' priority, relative to the current frame's
  RoamOptions roam;                 // maxErrorPx is taken from above
  SeedOptions seeds;
};

// The streaming options ROAM needs on top of `base`: the wedgie tables built on decode threads.
streaming::StreamingOptions streamingOptionsFor(const datasets::DatasetMeta& meta, streaming::StreamingOptions base);

// One drawable piece: plain data the caller turns into a render::TerrainDraw.
struct TerrainPiece {
  const TerrainMesh* mesh = nullptr;
  geo::TileId node;          // the selected tile it covers (untextured pieces: none)
  int heightLevelsUp = 0;    // heights come from this many levels above the node (at its centre)
  int imageryLevelsUp = -1;  // −1: no imagery on the GPU for it yet
  int imageryFallback = 0;   // levels coarser than the best tile for it (0: the best)
  int32_t imageryLayer = -1;
  glm::vec4 imageryUv{1.0f, 1.0f, 0.0f, 0.0f};
  int32_t previousLayer = -1;
  glm::vec4 previousUv{1.0f, 1.0f, 0.0f, 0.0f};
  float imageryBlend = 1.0f;
  // The plants' weight of this imagery (issue 18: species cross-fade with the imagery): with a
  // previous layer, imageryBlend; without one, the fade-in after the node's first imagery
  // arrived (0 → 1 over fadeS), so its plants grow in instead of appearing together.
  float plantBlend = 1.0f;
};

struct TerrainFrameFigures {
  uint64_t pieces = 0, triangles = 0;
  uint64_t fallbackPieces = 0;   // pieces drawn from an ancestor (heights or imagery)
  int maxLevelsCoarser = 0;      // the coarsest fallback, in levels
  uint64_t meshesBuilt = 0;      // piece meshes built this frame (ROAM output: all of them)
  double errorBoundPx = 0.0;     // the selection's bound this frame (maxErrorPx × relaxation)
  double relaxation = 1.0;       // 1: the wanted tiles fit the budgets
  double achievedErrorPx = 0.0;  // the largest on-screen error of a drawn ROAM leaf
  bool budgetLimited = false;    // the node or triangle budget cut refinement
  uint64_t lookAheadWants = 0;
  RoamFigures roam;
  int seedLevel = 0;
};

class StreamedTerrain {
 public:
  StreamedTerrain(streaming::TileStreamer& streamer, const geo::LocalFrame& frame, StreamedTerrainOptions options);

  // Step 1: the tiles this frame wants — heights and imagery of every selected node, most urgent
  // first — followed by look-ahead wants for the `ahead` views (deduplicated, lower priority).
  // `eye` is the same camera as `now`, for ROAM.
  std::vector<streaming::TileWant> wants(const SelectionView& now, const EyeView& eye,
                                         std::span<const SelectionView> ahead);

  // The same selections' wants again, after tiles turned out missing (their parents are wanted
  // instead): settled frames repeat settle() until the wants stop changing.
  std::vector<streaming::TileWant> wantsAgain();

  // Step 2, after streamer.update() and the uploads of this frame: ROAM over what is resident,
  // and the pieces to draw.
  std::span<const TerrainPiece> pieces(double timeS);

  // The seed triangles of the last pieces() call.
  std::span<const SeedTriangle> seedTriangles() const { return seeds_; }
  // Heights over the resident tiles (valid after pieces(), until the next streamer update).
  ResidentHeights& heights() { return *heights_; }
  const RoamTessellator& roam() const { return *roam_; }

  const TerrainFrameFigures& figures() const { return figures_; }

 private:
  struct NodeState {
    int imageryZ = -1;  // the imagery drawn last frame
    uint64_t lastFrame = 0;
    double imagerySwitchS = -1e9;
    double arrivalS = -1e9;  // when the node's first imagery arrived (after the first frame)
    int32_t previousLayer = -1;
    glm::vec4 previousUv{1.0f, 1.0f, 0.0f, 0.0f};
    int32_t layer = -1;
    glm::vec4 uv{1.0f, 1.0f, 0.0f, 0.0f};
  };

  void relax();
  NodeState startState(const geo::TileId& node) const;
  geo::TileId bestAvailable(streaming::TileLayer layer, const geo::TileId& tile) const;
  void imageryFor(TerrainPiece& p, NodeState& st, double timeS);
  void seedImagery(std::span<const geo::TileId> tiles, std::span<const int32_t> drawnPiece);

  streaming::TileStreamer* streamer_;
  geo::LocalFrame frame_;
  StreamedTerrainOptions options_;
  SelectionDataset dataset_;
  Selection selection_;
  EyeView eye_;
  std::vector<Selection> aheadSelections_;
  // The nodes' boxes kept from frame to frame: [0] for the camera's selection, [1 + i] for
  // look-ahead pose i's (each selection's own, as they are made side by side).
  std::vector<NodeBoxes> nodeBoxes_;
  double relaxation_ = 1.0;
  uint64_t frameNumber_ = 0;
  std::map<geo::TileId, NodeState> nodes_;
  std::unique_ptr<ResidentHeights> heights_;
  std::unique_ptr<RoamTessellator> roam_;
  PieceSet pieceSet_;
  std::vector<TerrainMesh> meshes_;
  std::vector<SeedTriangle> seeds_;
  std::vector<TerrainPiece> pieces_;
  TerrainFrameFigures figures_;
};

// Texture transform from a node's own [0,1]² uv to the tile `levelsUp` levels above it.
glm::vec4 ancestorUv(const geo::TileId& node, int levelsUp);

}  // namespace vegstream::terrain
