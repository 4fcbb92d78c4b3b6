// Every tree in a box (trees_in_box.h): the ground mosaics of the dataset, the tree grid's cells
// covering the box in the flight's frame, placed (vegetation/tree_placement.h, core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2, §3.3) and kept where the trunk stands in the box.

#include "scene/trees_in_box.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "geo/local_frame.h"
#include "scene/canopy_trees.h"
#include "scene/tree_ground.h"
#include "scene/box_dataset.h"
#include "vegetation/tree_placement.h"

namespace vegstream::scene {
namespace {

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, v);
  return buf;
}

bool inBox(const geo::Geodetic& at, const geo::GeoBounds& box) {
  return at.lonDeg >= box.westDeg && at.lonDeg < box.eastDeg && at.latDeg >= box.southDeg && at.latDeg < box.northDeg;
}

struct CellRange {
  int32_t cx0, cy0, cx1, cy1;  // half-open
};

// The cells whose trees may stand in the box: the box's outline (every 1/16 of each edge, at the
// dataset's lowest and highest ground: the frame's up tilts away from its origin, so a lon/lat
// maps to slightly different (x, y) at different heights) in the frame, and one cell around.
CellRange cellsCovering(const geo::GeoBounds& box, const geo::LocalFrame& frame, const vegetation::TreeGrid& grid,
                        double minHeightM, double maxHeightM) {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (int k = 0; k <= 16; ++k) {
    const double t = k / 16.0;
    const double lon = box.westDeg + t * (box.eastDeg - box.westDeg),
                 lat = box.southDeg + t * (box.northDeg - box.southDeg);
    const geo::Geodetic outline[4] = {
        {box.southDeg, lon, 0.0}, {box.northDeg, lon, 0.0}, {lat, box.westDeg, 0.0}, {lat, box.eastDeg, 0.0}};
    for (geo::Geodetic p : outline)
      for (double h : {minHeightM, maxHeightM}) {
        p.heightM = h;
        const glm::dvec3 e = frame.toLocal(p);
        x0 = std::min(x0, e.x);
        y0 = std::min(y0, e.y);
        x1 = std::max(x1, e.x);
        y1 = std::max(y1, e.y);
      }
  }
  return {vegetation::treeCellOf(grid, x0) - 1, vegetation::treeCellOf(grid, y0) - 1,
          vegetation::treeCellOf(grid, x1) + 2, vegetation::treeCellOf(grid, y1) + 2};
}

}  // namespace

Result<TreesInBox> treesInBox(const std::string& dataset, const geo::GeoBounds& box,
                              const vegetation::SpeciesCatalog& givenCatalog, const TreesInBoxOptions& options) {
  auto opened = openBoxDataset(dataset, box, options.boxName, givenCatalog);
  if (!opened) return opened.error();
  const BoxDataset& d = *opened;
  TreesInBox out;
  out.datasetName = d.meta.name;
  if (!vegetation::hasTrees(d.catalog)) return out;

  const geo::LocalFrame& frame = d.frame;  // the trees' ENU positions are those a flight places
  const vegetation::TreeGrid grid = vegetation::treeGridFor(d.catalog);
  const CellRange r = cellsCovering(box, frame, grid, d.meta.minHeightM, d.meta.maxHeightM);
  out.cellM = grid.cellM;
  out.cells = uint64_t(r.cx1 - r.cx0) * uint64_t(r.cy1 - r.cy0);
  // A cheap bound before reading the ground: at most 90 % of the cells hold a tree.
  const auto upperBound = static_cast<uint64_t>(double(out.cells) * double(vegetation::kTreeCellShare));
  if (upperBound > 4 * options.maxTrees)
    return makeError(ErrorKind::InvalidInput, options.boxName + ": the box holds up to " + std::to_string(upperBound) +
                                                  " trees (" + std::to_string(out.cells) + " cells of " +
                                                  fmt("%.2f", grid.cellM) + " m), more than " + options.maxTreesName +
                                                  " " + std::to_string(options.maxTrees) + "; give a smaller box or " +
                                                  options.maxTreesName + " " + std::to_string(upperBound));

  auto ground = TreeGround::load(*d.source, d.meta, frame, options.ground);
  if (!ground) return ground.error();
  if (d.meta.landcover) ground->allowLandcover(landcoverMasks(d.catalog, *d.meta.landcover));
  out.groundZoom = ground->zoom();
  std::vector<vegetation::PlacedTree> placed;
  auto canopy = CanopyTrees::load(*d.source, d.meta, frame, &box);
  if (!canopy) return canopy.error();
  placeTreesWithCanopy(canopy->get(), d.catalog, grid, r.cx0, r.cy0, r.cx1, r.cy1, ground->at(), placed);
  uint64_t count = 0;
  for (const vegetation::PlacedTree& t : placed) {
    const geo::Geodetic at = frame.toGeodetic({t.x, t.y, t.z});
    out.crowns.push_back({at, t.crownM});
    if (!inBox(at, box)) continue;
    ++count;
    if (out.trees.size() < options.maxTrees)
      out.trees.push_back({at, t.species, t.seed, t.heightM, t.crownM, t.sPrime});
  }
  if (count > options.maxTrees)
    return makeError(ErrorKind::InvalidInput, options.boxName + ": the box holds " + std::to_string(count) +
                                                  " trees, more than " + options.maxTreesName + " " +
                                                  std::to_string(options.maxTrees) + "; give a smaller box or " +
                                                  options.maxTreesName + " " + std::to_string(count));
  return out;
}

}  // namespace vegstream::scene
