#pragma once
// Trees at the crowns of the dataset's canopy height model (issue 41 item 3, `import
// --canopy-height`): where the canopy layer has heights, the trees are the tops found in it
// (vegetation/crown_detection.h, Popescu & Wynne 2004) — their positions, heights and crown
// widths from the data, their species from the imagery under them (core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 eq. 16–18: chooseSpecies; a winner that is no
// tree gives way to the tree species of best colour score, s′ = 1); elsewhere the trees of
// vegetation/tree_placement.h as before (a placed tree whose trunk stands where the layer has a
// height is dropped: the CHM speaks for that ground).
//
// View-independent, cell by cell like the placement: the layer is read at its own zoom (the Web
// Mercator pixel grid of canopy.zoom, fixed for the dataset), detection runs on the pixels around
// the cells asked for plus crown_detection's margin, so a top's position depends on the pixels
// near it only; its trunk stands in exactly one grid cell (floor of its local x, y), the cell that
// owns it. Positions: the top's pixel coordinates → lon/lat → the local frame at the ground's
// height there (TreeGroundAt's z); ground metres per pixel are those at the frame's origin.
// A tree's seed is a Philox word of its top's pixel. Cells hold more than one tree where the
// canopy is denser than the grid (vegetation/canopy_cells.h then thins the plants under one).
//
// The layer is read whole at load (at most kMaxCanopyTiles tiles; a larger layer is refused with
// InvalidInput so that the caller can go on without it).

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "core/result.h"
#include "datasets/dataset_format.h"
#include "geo/local_frame.h"
#include "geo/xyz_tiles.h"
#include "streaming/tile_source.h"
#include "vegetation/crown_detection.h"
#include "vegetation/species_catalog.h"
#include "vegetation/tree_placement.h"

namespace vegstream::scene {

inline constexpr uint64_t kMaxCanopyTiles = 2048;  // 256 MiB of 16-bit heights
// Around a load's area: more than a tree cell, the cells' slack and the detection's margin.
inline constexpr double kAreaMarginM = 250.0;

class CanopyTrees {
 public:
  // nullptr when the dataset has no canopy layer. `area`: only the tiles within kAreaMarginM of
  // it are read (trees_in_box: the box; the trees of the area are the same as with the whole
  // layer); null: the whole layer. Errors: a corrupt tile (named), more tiles than
  // kMaxCanopyTiles, Io from the source.
  static Result<std::shared_ptr<const CanopyTrees>> load(streaming::TileSource& source,
                                                         const datasets::DatasetMeta& meta,
                                                         const geo::LocalFrame& frame,
                                                         const geo::GeoBounds* area = nullptr);

  // Whether the layer has a height under the local point (x, y, z).
  bool covers(double x, double y, double z) const;
  // The CHM's trees whose trunks stand in cells [cx0, cx1) × [cy0, cy1), appended to `out` in
  // the cells' row-major order (cy, then cx, then y, x). No tree where the ground is invalid.
  void treesInCells(const vegetation::SpeciesCatalog& catalog, const vegetation::TreeGrid& grid, int32_t cx0,
                    int32_t cy0, int32_t cx1, int32_t cy1, const vegetation::TreeGroundAt& ground,
                    std::vector<vegetation::PlacedTree>& out) const;
  int zoom() const { return zoom_; }
  size_t tiles() const { return tiles_.size(); }

 private:
  CanopyTrees(int zoom, const geo::LocalFrame& frame) : zoom_(zoom), frame_(frame) {}
  float heightAt(int64_t gx, int64_t gy) const;  // global pixel at zoom_; NaN: no data
  struct PixelWindow {
    int64_t gx0 = 0, gy0 = 0;  // global pixel of its top-left
    int w = 0, h = 0;
    std::vector<float> heights;  // w × h, NaN = no data
  };
  // The layer's pixels under cells [cx0, cx1) × [cy0, cy1) and the detection's margin around.
  PixelWindow windowOver(const vegetation::TreeGrid& grid, int32_t cx0, int32_t cy0, int32_t cx1, int32_t cy1) const;

  int zoom_;
  geo::LocalFrame frame_;
  vegetation::CrownDetectionOptions detection_;
  std::map<std::pair<int, int>, std::vector<uint16_t>> tiles_;  // (x, y) → decimetres
};

// The trees of cells [cx0, cx1) × [cy0, cy1): vegetation::placeTreesInCells, and with a canopy
// layer its trees where it has heights (above). Both the renderer's tree field and `plants` call it.
void placeTreesWithCanopy(const CanopyTrees* canopy, const vegetation::SpeciesCatalog& catalog,
                          const vegetation::TreeGrid& grid, int32_t cx0, int32_t cy0, int32_t cx1, int32_t cy1,
                          const vegetation::TreeGroundAt& ground, std::vector<vegetation::PlacedTree>& out);

}  // namespace vegstream::scene
