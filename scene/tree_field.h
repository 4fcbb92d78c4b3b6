#pragma once
// The trees around the camera (issue 20): world tiles of the tree grid's cells
// (vegetation/tree_placement.h) within the tree horizon, placed once each — view-independent:
// a tile's trees depend only on the ground — and given pages of the renderer's tree pool
// (render/tree_layout.h), nearest tiles first. Budgets as cesium-native's tile loads: a tile
// that leaves the horizon frees its pages; when the pool is full, the farthest tiles give theirs
// to nearer ones, and the tiles left without pages are not drawn (the terrain's own colour shows
// there; `budgetBound` says so). Settled frames place every wanted tile before drawing
// (deterministic); realtime frames place at most `placementsPerFrame`, nearest first.

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "render/tree_layout.h"
#include "scene/canopy_trees.h"
#include "scene/tree_field_figures.h"
#include "vegetation/canopy_cells.h"
#include "vegetation/species_catalog.h"
#include "vegetation/tree_placement.h"

namespace vegstream::scene {

struct TreeFieldOptions {
  render::TreeLodDistances lod;  // lod.horizonM: where trees end
  uint32_t tileCells = 48;       // a tile is tileCells × tileCells grid cells
  uint32_t placementsPerFrame = 2;
  bool fades = true;
  bool shadows = true;
  bool cores = true;
};

class TreeField {
 public:
  // `firstModel[s]`: the renderer's first model of catalog species s, with `variants` each.
  TreeField(const vegetation::SpeciesCatalog& catalog, vegetation::TreeGroundAt ground, const TreeFieldOptions& options,
            std::vector<uint32_t> firstModel, uint32_t variants, uint32_t pageCapacity);

  // The trees of a frame for a camera at `cameraEnu` (the local frame); valid until the next call.
  const render::TreeRequest& prepare(const glm::dvec3& cameraEnu, bool settled);
  const TreeFieldFigures& figures() const { return figures_; }
  // The crowns about `cameraEnu` of the trees drawn (tiles with pages), for the plants to thin
  // under (vegetation/canopy_cells.h); after prepare().
  void fillCanopy(const glm::dvec3& cameraEnu, vegetation::CanopyTable& out);
  const vegetation::TreeGrid& grid() const { return grid_; }
  // Trees at the canopy layer's crowns where it has heights (canopy_trees.h); before any prepare().
  void setCanopy(std::shared_ptr<const CanopyTrees> canopy) { canopy_ = std::move(canopy); }

 private:
  using TileKey = std::pair<int32_t, int32_t>;
  struct Tile {
    std::vector<render::TreeInstanceGpu> trees;
    std::vector<uint32_t> pages;  // empty: not drawn
    bool placed = false;
  };
  void place(const TileKey& key, Tile& tile);
  void freePages(Tile& tile);
  // prepare()'s steps: the tiles any part of which lies within the horizon, nearest first; the
  // others dropped and the wanted placed (in a realtime frame a few); their pages; the drawn
  // tiles' figures (returns one past the highest page used).
  using Wanted = std::vector<std::pair<double, TileKey>>;
  Wanted wantedTiles(const glm::dvec3& camera) const;
  void placeWanted(const Wanted& wanted, bool settled);
  void assignPages(const Wanted& wanted);
  uint32_t countDrawn();

  const vegetation::SpeciesCatalog* catalog_;
  vegetation::TreeGroundAt ground_;
  TreeFieldOptions options_;
  vegetation::TreeGrid grid_;
  std::vector<uint32_t> firstModel_;
  uint32_t variants_;
  std::map<TileKey, Tile> tiles_;
  std::vector<uint32_t> freePages_;
  std::vector<uint32_t> pageCounts_;
  std::vector<render::TreePageUpload> uploads_;
  render::TreeRequest request_;
  TreeFieldFigures figures_;
  std::vector<vegetation::PlacedTree> scratch_;
  std::vector<vegetation::CanopyTree> canopyTrees_;
  std::shared_ptr<const CanopyTrees> canopy_;
};

}  // namespace vegstream::scene
