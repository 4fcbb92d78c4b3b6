#pragma once
// The terrain over streamed tiles: each frame it says which tiles it wants (the chunked-LOD
// selection of tile_selection.h for the camera, plus prefetches for the poses expected in the
// next seconds), and after the streamer's update it turns the selection into drawable pieces,
// each drawn from the nearest resident heights and imagery — the node's own tiles or an
// ancestor's, never a hole.
//
// When a finer source arrives for a node (its own tile, or the node appears by a split), the
// piece morphs from the surface drawn before (geomorphing through TerrainVertex::morphDelta) and
// its imagery fades in over the layer drawn before, both over `fadeS` seconds of flight time.
// When the wanted tiles do not fit the CPU or GPU budget, the error bound relaxes (×1.5 per
// frame) until they do, and recovers slowly when there is room again; figures() says by how much.
//
// Frame thread only. Deterministic for a deterministic streamer (settled recordings).

#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "geo/local_frame.h"
#include "streaming/tile_streamer.h"
#include "terrain/terrain_mesh.h"
#include "terrain/tile_node_mesh.h"
#include "terrain/tile_selection.h"

namespace vegstream::terrain {

struct StreamedTerrainOptions {
  double maxErrorPx = 2.0;           // screen-space error bound (relaxed under budget pressure)
  int maxNodes = 384;                // most pieces drawn
  double fadeS = 0.5;                // morph / imagery fade-in time, seconds of flight
  double lookAheadPriority = 0.25;   // look-ahead wants' priority, relative to the current frame's
};

// One drawable piece: plain data the caller turns into a render::TerrainDraw.
struct TerrainPiece {
  const TerrainMesh* mesh = nullptr;
  geo::TileId node;
  int heightLevelsUp = 0;            // heights drawn from this many levels above the node (nodes
                                     // finer than the dataset's max zoom always draw its tiles)
  int imageryLevelsUp = -1;          // −1: no imagery on the GPU for it yet
  int imageryFallback = 0;           // levels coarser than the best tile for it (0: the best)
  int32_t imageryLayer = -1;
  glm::vec4 imageryUv{1.0f, 1.0f, 0.0f, 0.0f};
  int32_t previousLayer = -1;
  glm::vec4 previousUv{1.0f, 1.0f, 0.0f, 0.0f};
  float imageryBlend = 1.0f;
  float morph = 0.0f;
};

struct TerrainFrameFigures {
  uint64_t pieces = 0, triangles = 0;
  uint64_t fallbackPieces = 0;       // pieces drawn from an ancestor (heights or imagery)
  int maxLevelsCoarser = 0;          // the coarsest fallback, in levels
  uint64_t meshesBuilt = 0;          // node meshes built this frame (the rest came from the cache)
  double errorBoundPx = 0.0;         // the bound used this frame (maxErrorPx × relaxation)
  double relaxation = 1.0;           // 1: the wanted tiles fit the budgets
  double achievedErrorPx = 0.0;
  bool budgetLimited = false;        // the node budget cut refinement
  uint64_t lookAheadWants = 0;
};

class StreamedTerrain {
 public:
  StreamedTerrain(streaming::TileStreamer& streamer, const geo::LocalFrame& frame, StreamedTerrainOptions options);

  // Step 1: the tiles this frame wants — heights and imagery of every selected node, most urgent
  // first — followed by look-ahead wants for the `ahead` views (deduplicated, lower priority).
  std::vector<streaming::TileWant> wants(const SelectionView& now, std::span<const SelectionView> ahead);

  // The same selections' wants again, after tiles turned out missing (their parents are wanted
  // instead): settled frames repeat settle() until the wants stop changing.
  std::vector<streaming::TileWant> wantsAgain();

  // Step 2, after streamer.update() and the uploads of this frame: the pieces to draw.
  std::span<const TerrainPiece> pieces(double timeS);

  const TerrainFrameFigures& figures() const { return figures_; }

 private:
  struct NodeState {
    int heightZ = -1, imageryZ = -1;      // sources drawn last frame
    uint64_t lastFrame = 0;
    double heightSwitchS = -1e9;          // when the height source last got finer
    int morphFromZ = -1;                  // the coarse source it morphs from
    double imagerySwitchS = -1e9;
    int32_t previousLayer = -1;
    glm::vec4 previousUv{1.0f, 1.0f, 0.0f, 0.0f};
    int32_t layer = -1;
    glm::vec4 uv{1.0f, 1.0f, 0.0f, 0.0f};
  };
  struct MeshKey {
    geo::TileId node;
    int sourceZ = 0, coarseZ = -1;
    auto operator<=>(const MeshKey&) const = default;
  };
  struct CachedMesh {
    NodeMesh mesh;
    uint64_t lastFrame = 0;
  };

  void relax();
  const TerrainMesh& meshFor(const geo::TileId& node, const streaming::ResidentTile& source,
                             const streaming::ResidentTile* coarse);
  NodeState startState(const geo::TileId& node) const;
  geo::TileId tileFor(const geo::TileId& node) const;
  geo::TileId bestAvailable(streaming::TileLayer layer, const geo::TileId& tile) const;  // the tile a node wants: itself, or its max-zoom ancestor

  streaming::TileStreamer* streamer_;
  geo::LocalFrame frame_;
  StreamedTerrainOptions options_;
  SelectionDataset dataset_;           // maxZoom: the dataset's + kBeyondMaxZoom
  int tileMaxZoom_ = 0;                // the dataset's finest tiles
  Selection selection_;
  std::vector<Selection> aheadSelections_;
  double relaxation_ = 1.0;
  uint64_t frameNumber_ = 0;
  std::map<geo::TileId, NodeState> nodes_;
  std::map<MeshKey, CachedMesh> meshes_;
  std::vector<TerrainPiece> pieces_;
  TerrainFrameFigures figures_;
};

// Texture transform from a node's own [0,1]² uv to the tile `levelsUp` levels above it.
glm::vec4 ancestorUv(const geo::TileId& node, int levelsUp);

}  // namespace vegstream::terrain
