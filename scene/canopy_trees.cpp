// Trees at the canopy height model's crowns where the dataset has one (canopy_trees.h; Popescu &
// Wynne 2004 through vegetation/crown_detection.h), the placement of tree_placement.h elsewhere.

#include "scene/canopy_trees.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "datasets/canopy.h"
#include "vegetation/colour_score.h"
#include "vegetation/philox.h"
#include "vegetation/species_choice.h"
#include "vegetation/tree_niche.h"

namespace vegstream::scene {
namespace {

constexpr uint32_t kCanopySeedKey = 0xC4A0B7u;   // the Philox key of a canopy tree's seed
constexpr uint32_t kCanopyNicheKey = 0xC4A0B8u;  // … of its choice among the trees
constexpr double kSlackM = 10.0;                // around the cells: the frame's tilt, rounding

// The imagery's species at the ground as the placement chooses it (tree_placement.h): the
// calibrated colour among the species the landcover class allows, a winner that is no tree giving
// way to the claiming tree species of best colour score (the CHM says a tree stands here); then
// the choice among the trees by colour and niche (tree_niche.h). −1: the class allows no tree.
vegetation::SpeciesChoice treeSpeciesAt(const vegetation::SpeciesCatalog& catalog,
                                        const vegetation::TreeGroundSample& g, float z, float zNiche) {
  namespace veg = vegetation;
  const veg::GroundColour colour = veg::calibratedGround(catalog.calibration, g.linearRgb);
  veg::SpeciesChoice pick = veg::chooseSpecies(catalog, colour.hsv, z, g.ndvi, colour.exg, g.allowed);
  if (pick.species < 0 || !veg::isTree(catalog.species[static_cast<size_t>(pick.species)])) {
    pick = {};
    float best = -INFINITY;
    for (size_t s = 0; s < catalog.species.size() && s < 32; ++s) {
      const veg::Species& sp = catalog.species[s];
      if (!veg::isTree(sp) || !sp.tree.claimsGround || ((g.allowed >> s) & 1u) == 0u) continue;
      const float l = veg::logColourScore(sp.score, colour.hsv, g.ndvi, colour.exg);
      if (l > best) best = l, pick.species = static_cast<int>(s);
    }
    if (pick.species < 0) return pick;
    pick.sPrime = 1.0f;
  }
  const veg::SpeciesChoice tree = veg::chooseTreeSpecies(catalog, pick.species, colour, g.ndvi, g.site, zNiche, g.allowed);
  if (tree.species >= 0) pick.species = tree.species;
  return pick;
}

}  // namespace

Result<std::shared_ptr<const CanopyTrees>> CanopyTrees::load(streaming::TileSource& source,
                                                             const datasets::DatasetMeta& meta,
                                                             const geo::LocalFrame& frame,
                                                             const geo::GeoBounds* area) {
  if (!meta.canopyZoom) return std::shared_ptr<const CanopyTrees>();
  const int z = *meta.canopyZoom;
  geo::GeoBounds read = meta.bounds;
  if (area) {
    const double dLat = kAreaMarginM / 111000.0;
    const double dLon = dLat / std::max(0.05, std::cos(area->centre().y * 3.14159265358979323846 / 180.0));
    read = {std::max(read.westDeg, area->westDeg - dLon), std::max(read.southDeg, area->southDeg - dLat),
            std::min(read.eastDeg, area->eastDeg + dLon), std::min(read.northDeg, area->northDeg + dLat)};
  }
  uint64_t count = 0;
  for (const auto& r : geo::tileRangesCovering(read, z)) count += static_cast<uint64_t>(r.count());
  if (count > kMaxCanopyTiles)
    return makeError(ErrorKind::InvalidInput,
                     source.describe() + ": the canopy layer covers " + std::to_string(count) + " tiles at zoom " +
                         std::to_string(z) + ", more than the " + std::to_string(kMaxCanopyTiles) +
                         " the trees read at once; its trees are placed from the imagery instead");
  std::shared_ptr<CanopyTrees> c(new CanopyTrees(z, frame));
  c->detection_.pixelM = static_cast<float>(geo::groundResolution(frame.origin().latDeg, z, datasets::kTileSize));
  for (const geo::TileId& id : geo::tilesCovering(read, z)) {
    const std::string path = datasets::canopyTilePath({}, id).generic_string();
    auto bytes = source.readText(path);
    if (!bytes) {
      if (bytes.error().kind == ErrorKind::NotFound) continue;
      return bytes.error();
    }
    auto t = datasets::decodeCanopyTile({reinterpret_cast<const uint8_t*>(bytes->data()), bytes->size()}, id,
                                        source.describe() + "/" + path, meta.tileSize);
    if (!t) return t.error();
    c->tiles_.emplace(std::make_pair(id.x, id.y), std::move(t->decimetres));
  }
  return std::shared_ptr<const CanopyTrees>(std::move(c));
}

float CanopyTrees::heightAt(int64_t gx, int64_t gy) const {
  const int n = datasets::kTileSize;
  if (gx < 0 || gy < 0) return NAN;
  const auto it = tiles_.find({static_cast<int>(gx / n), static_cast<int>(gy / n)});
  if (it == tiles_.end()) return NAN;
  return datasets::canopyHeightOf(it->second[static_cast<size_t>(gy % n) * size_t(n) + static_cast<size_t>(gx % n)]);
}

bool CanopyTrees::covers(double x, double y, double z) const {
  const geo::Geodetic g = frame_.toGeodetic({x, y, z});
  const glm::dvec2 t = geo::lonLatToTileXY({g.lonDeg, g.latDeg}, zoom_) * double(datasets::kTileSize);
  return !std::isnan(heightAt(static_cast<int64_t>(std::floor(t.x)), static_cast<int64_t>(std::floor(t.y))));
}

CanopyTrees::PixelWindow CanopyTrees::windowOver(const vegetation::TreeGrid& grid, int32_t cx0, int32_t cy0,
                                                 int32_t cx1, int32_t cy1) const {
  const double n = datasets::kTileSize;
  // The global pixels under the cells (their corners at the frame's height 0, with slack), plus
  // the detection's margin.
  double px0 = INFINITY, py0 = INFINITY, px1 = -INFINITY, py1 = -INFINITY;
  for (int k = 0; k < 4; ++k) {
    const double x = (k & 1 ? cx1 : cx0) * grid.cellM + (k & 1 ? kSlackM : -kSlackM);
    const double y = (k & 2 ? cy1 : cy0) * grid.cellM + (k & 2 ? kSlackM : -kSlackM);
    const geo::Geodetic g = frame_.toGeodetic({x, y, 0.0});
    const glm::dvec2 t = geo::lonLatToTileXY({g.lonDeg, g.latDeg}, zoom_) * n;
    px0 = std::min(px0, t.x), py0 = std::min(py0, t.y), px1 = std::max(px1, t.x), py1 = std::max(py1, t.y);
  }
  const int m = vegetation::marginPixels(detection_);
  PixelWindow w;
  w.gx0 = static_cast<int64_t>(std::floor(px0)) - m;
  w.gy0 = static_cast<int64_t>(std::floor(py0)) - m;
  w.w = static_cast<int>(static_cast<int64_t>(std::ceil(px1)) + m - w.gx0);
  w.h = static_cast<int>(static_cast<int64_t>(std::ceil(py1)) + m - w.gy0);
  w.heights.resize(size_t(w.w) * size_t(w.h));
  for (int r = 0; r < w.h; ++r)
    for (int c = 0; c < w.w; ++c) w.heights[size_t(r) * size_t(w.w) + size_t(c)] = heightAt(w.gx0 + c, w.gy0 + r);
  return w;
}

void CanopyTrees::treesInCells(const vegetation::SpeciesCatalog& catalog, const vegetation::TreeGrid& grid,
                               int32_t cx0, int32_t cy0, int32_t cx1, int32_t cy1,
                               const vegetation::TreeGroundAt& ground, std::vector<vegetation::PlacedTree>& out) const {
  if (tiles_.empty() || cx0 >= cx1 || cy0 >= cy1) return;
  const double n = datasets::kTileSize;
  const PixelWindow win = windowOver(grid, cx0, cy0, cx1, cy1);
  const int64_t gx0 = win.gx0, gy0 = win.gy0;
  std::vector<std::tuple<int32_t, int32_t, vegetation::PlacedTree>> found;
  for (const vegetation::DetectedCrown& crown : vegetation::detectCrowns(win.heights, win.w, win.h, detection_)) {
    const glm::dvec2 tileXY{(double(gx0) + crown.col) / n, (double(gy0) + crown.row) / n};
    const glm::dvec2 ll = geo::tileXYToLonLat(tileXY, zoom_);
    // On the ground: the local point at height 0, the ground's z there, then the point again at
    // that ground's ellipsoidal height (the frame's up tilts away from its origin).
    glm::dvec3 p = frame_.toLocal({ll.y, ll.x, 0.0});
    const vegetation::TreeGroundSample first = ground(p.x, p.y);
    if (!first.valid) continue;
    p = frame_.toLocal({ll.y, ll.x, frame_.toGeodetic({p.x, p.y, first.heightM}).heightM});
    const int32_t cx = vegetation::treeCellOf(grid, p.x), cy = vegetation::treeCellOf(grid, p.y);
    if (cx < cx0 || cx >= cx1 || cy < cy0 || cy >= cy1) continue;
    const vegetation::TreeGroundSample g = ground(p.x, p.y);
    if (!g.valid) continue;
    const auto ix = static_cast<uint32_t>(gx0 + static_cast<int64_t>(std::floor(crown.col)));
    const auto iy = static_cast<uint32_t>(gy0 + static_cast<int64_t>(std::floor(crown.row)));
    const vegetation::Philox2x32Out words = vegetation::philox(ix, iy, kCanopySeedKey ^ static_cast<uint32_t>(zoom_));
    const vegetation::Philox2x32Out niche = vegetation::philox(ix, iy, kCanopyNicheKey ^ static_cast<uint32_t>(zoom_));
    const vegetation::SpeciesChoice pick = treeSpeciesAt(catalog, g, vegetation::u01(words.y), vegetation::u01(niche.x));
    if (pick.species < 0) continue;
    vegetation::PlacedTree t;
    t.x = p.x;
    t.y = p.y;
    t.z = g.heightM;
    t.species = static_cast<uint32_t>(pick.species);
    t.seed = words.x;
    t.heightM = crown.heightM;
    t.crownM = 2.0f * crown.crownRadiusM;
    t.sPrime = pick.sPrime;
    t.groundLinear = g.linearRgb;
    found.emplace_back(cy, cx, t);
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
    const auto& ta = std::get<2>(a);
    const auto& tb = std::get<2>(b);
    return std::tie(std::get<0>(a), std::get<1>(a), ta.y, ta.x) < std::tie(std::get<0>(b), std::get<1>(b), tb.y, tb.x);
  });
  for (auto& f : found) out.push_back(std::get<2>(f));
}

void placeTreesWithCanopy(const CanopyTrees* canopy, const vegetation::SpeciesCatalog& catalog,
                          const vegetation::TreeGrid& grid, int32_t cx0, int32_t cy0, int32_t cx1, int32_t cy1,
                          const vegetation::TreeGroundAt& ground, std::vector<vegetation::PlacedTree>& out) {
  if (!canopy) {
    vegetation::placeTreesInCells(catalog, grid, cx0, cy0, cx1, cy1, ground, out);
    return;
  }
  std::vector<vegetation::PlacedTree> placed;
  vegetation::placeTreesInCells(catalog, grid, cx0, cy0, cx1, cy1, ground, placed);
  for (const vegetation::PlacedTree& t : placed)
    if (!canopy->covers(t.x, t.y, t.z)) out.push_back(t);
  canopy->treesInCells(catalog, grid, cx0, cy0, cx1, cy1, ground, out);
}

}  // namespace vegstream::scene
