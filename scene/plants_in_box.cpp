// Every plant in a box (plants_in_box.h): seed triangles of the box at full density, heights
// through the streamer → clusters and species from the imagery colour → plants, kept where
// their root lies in the box.

#include "scene/plants_in_box.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "geo/xyz_tiles.h"
#include "scene/settled_tiles.h"
#include "scene/box_dataset.h"
#include "scene/landcover_masks.h"
#include "streaming/dataset_snapshot.h"
#include "terrain/resident_heights.h"
#include "terrain/seed_region.h"
#include "terrain/seed_triangles.h"
#include "vegetation/canopy_cells.h"
#include "vegetation/imagery_texels.h"
#include "vegetation/plant_seeding.h"

namespace vegstream::scene {
namespace {

std::string plural(uint64_t n, const char* what) { return std::to_string(n) + " " + what + (n == 1 ? "" : "s"); }

// The imagery tile a triangle's plants take their colour from: the finest over its centroid at
// or above the max zoom (the renderer's pieces at full detail draw the finest imagery).
const datasets::ColorTile* imageryOver(SettledTiles& tiles, const terrain::BintreeGrid& grid, int maxZoom,
                                       const terrain::TriCorners& t) {
  const geo::TileId finest = grid.square(t, 2 * (maxZoom - grid.rootZoom()));
  const streaming::ResidentTile* r = tiles.finest({streaming::TileLayer::Imagery, finest});
  return r && r->colors ? r->colors.get() : nullptr;
}

// The species the landcover class under a point of an imagery tile allows (landcover_masks.h):
// the landcover tile of the same id, read once, the texel whose square holds the point (classes
// are never blended). Every species where the dataset has no layer.
struct LandcoverLookup {
  streaming::TileSource* source = nullptr;  // null: no landcover layer
  LandcoverMasks masks{};
  std::map<geo::TileId, std::vector<uint8_t>> tiles;
  std::optional<Error> error;

  vegetation::SpeciesMask at(const datasets::ColorTile& c, glm::vec2 uv) {
    if (!source) return vegetation::kAllSpecies;
    auto it = tiles.find(c.id);
    if (it == tiles.end()) {
      auto classes = streaming::loadLandcoverClasses(*source, c.id, c.size);
      if (!classes && !error) error = classes.error();
      it = tiles.emplace(c.id, classes ? std::move(*classes) : std::vector<uint8_t>{}).first;
    }
    if (it->second.empty()) return masks[0];  // no landcover tile here: no class
    const int n = c.size;
    const int x = std::clamp(static_cast<int>(std::floor(uv.x * float(n))), 0, n - 1);
    const int y = std::clamp(static_cast<int>(std::floor(uv.y * float(n))), 0, n - 1);
    return masks[it->second[static_cast<size_t>(y) * static_cast<size_t>(n) + static_cast<size_t>(x)]];
  }
};

// Grows every seed triangle's plants and keeps those in the box (counting all of them).
void grow(const terrain::BintreeGrid& grid, const geo::LocalFrame& frame, const terrain::SeedRegion& region,
          const geo::GeoBounds& box, const vegetation::SpeciesCatalog& catalog,
          const vegetation::SeedingOptions& seeding, std::span<const vegetation::CanopyTree> crowns,
          const vegetation::TreeGrid& treeGrid, SettledTiles& tiles, int maxZoom, uint64_t maxPlants,
          LandcoverLookup& landcover, PlantsInBox& out, uint64_t& count) {
  std::vector<vegetation::PlantCluster> clusters;
  std::vector<vegetation::Plant> plants;
  // The crowns' table about a point near the triangles (a flight's is about its camera): the
  // corner of the kCanopyCentreM square grid nearest each triangle, well inside the table's
  // window; a triangle's plants then do not depend on the box (a sub-box lists the same).
  constexpr double kCanopyCentreM = 128.0;
  vegetation::CanopyTable canopy;
  bool canopyMade = false;
  vegetation::SeedingOptions options = seeding;
  for (size_t i = 0; i < region.triangles.size(); ++i) {
    const terrain::RegionSeedTriangle& s = region.triangles[i];
    if (!crowns.empty()) {
      const glm::dvec3 centre(std::round(s.world[0].x / kCanopyCentreM) * kCanopyCentreM,
                              std::round(s.world[0].y / kCanopyCentreM) * kCanopyCentreM, 0.0);
      if (!canopyMade || centre != canopy.camera) {
        vegetation::fillCanopyTable(treeGrid, centre, crowns, canopy);
        canopyMade = true;
      }
      options.canopy = &canopy;
    }
    const datasets::ColorTile* c = imageryOver(tiles, grid, maxZoom, s.corners);
    if (!c) continue;  // no imagery over it: no colour, no species (as a flight without it)
    // uv of each vertex in that tile, as StreamedTerrain::seedImagery gives the GPU (float).
    const terrain::GridPoint corners[3] = {s.corners.apex, s.corners.left, s.corners.right};
    glm::vec2 uv[3];
    for (int k = 0; k < 3; ++k) uv[k] = glm::vec2(grid.tileXY(corners[k], c->id.z) - glm::dvec2(c->id.x, c->id.y));
    const vegetation::ImageryTexels texels{c->rgba.data(), static_cast<uint32_t>(c->size),
                                           c->ndvi.empty() ? nullptr : c->ndvi.data()};
    const vegetation::BaseColourAt colourAt = [&](glm::vec2 r) -> vegetation::GroundSample {
      const glm::vec2 at = uv[0] + r.x * (uv[1] - uv[0]) + r.y * (uv[2] - uv[0]);
      return {vegetation::sampleImageryLinear(texels, at), vegetation::sampleImageryNdvi(texels, at),
              landcover.at(*c, at)};
    };
    const vegetation::SeedTriangleInput input{s.key, s.world, s.plantCount};
    clusters.clear();
    plants.clear();
    vegetation::classifyTriangle(input, static_cast<uint32_t>(i), catalog, options, colourAt, clusters);
    vegetation::growPlants(input, clusters, catalog, options, plants);
    for (const vegetation::Plant& p : plants) {
      const geo::Geodetic at = frame.toGeodetic(p.position);
      if (at.lonDeg < box.westDeg || at.lonDeg >= box.eastDeg || at.latDeg < box.southDeg || at.latDeg >= box.northDeg)
        continue;
      ++count;
      if (out.plants.size() < maxPlants) out.plants.push_back({at, p.species, p.heightM, p.stiffness, p.sPrime});
    }
  }
}

// "more than --max-plants N": the box grows howMany, n of them.
Error tooManyPlants(const PlantsInBoxOptions& options, const std::string& howMany, uint64_t n) {
  return makeError(ErrorKind::InvalidInput, options.boxName + ": " + howMany + ", more than " + options.maxPlantsName +
                                                " " + std::to_string(options.maxPlants) + "; give a smaller box or " +
                                                options.maxPlantsName + " " + std::to_string(n));
}

// Triangles × their flat area × the densest species: more than 4 × the most plants is refused.
Status checkUpperBound(const terrain::BintreeGrid& grid, const geo::TileRange& roots,
                       const terrain::SeedRegionQuery& query, double lat, const PlantsInBoxOptions& options) {
  const uint64_t triangles = terrain::countSeedTrianglesIn(grid, roots, query);
  const double perTriangle = query.densityM2 * terrain::triangleAreaM2(grid, query.seedLevel, lat);
  const auto upperBound = static_cast<uint64_t>(double(triangles) * perTriangle);
  if (upperBound > 4 * options.maxPlants)
    return tooManyPlants(options,
                         "the box grows up to " + plural(upperBound, "plant") + " (" +
                             plural(triangles, "seed triangle") + " × " + std::to_string(int(perTriangle)) + ")",
                         upperBound);
  return {};
}

// The box's finest tiles of both layers, settled in one go.
void prefetchBox(SettledTiles& tiles, const geo::GeoBounds& box, int maxZoom) {
  std::vector<streaming::TileKey> wanted;
  for (const geo::TileId& id : geo::tilesCovering(box, maxZoom))
    for (streaming::TileLayer layer : {streaming::TileLayer::Height, streaming::TileLayer::Imagery})
      wanted.push_back({layer, id});
  tiles.prefetch(wanted);
}

// The given crowns in the box's frame; none when the catalog has no trees.
std::vector<vegetation::CanopyTree> boxCrowns(const PlantsInBoxOptions& options, const geo::LocalFrame& frame,
                                              const vegetation::SpeciesCatalog& catalog) {
  std::vector<vegetation::CanopyTree> crowns;
  for (const BoxCrown& c : options.crowns) crowns.push_back({frame.toLocal(c.at), c.crownM});
  if (!vegetation::hasTrees(catalog)) crowns.clear();
  return crowns;
}

}  // namespace

Result<PlantsInBox> plantsInBox(const std::string& dataset, const geo::GeoBounds& box,
                                const vegetation::SpeciesCatalog& givenCatalog, const PlantsInBoxOptions& options) {
  auto opened = openBoxDataset(dataset, box, options.boxName, givenCatalog);
  if (!opened) return opened.error();
  const BoxDataset& d = *opened;
  const geo::GeoBounds& b = d.meta.bounds;

  // The renderer's grid, seed level and roots (StreamedTerrain): the same triangles, keys and
  // vertices as in a flight.
  const terrain::SeedOptions seedOptions;
  const double lat = b.centre().y;
  const terrain::BintreeGrid grid =
      terrain::gridForSeeds(d.meta.minZoom, d.meta.maxZoom, lat, seedOptions.targetAreaM2);
  const geo::TileRange roots = geo::tileRangesCovering(b, d.meta.minZoom).front();
  const geo::LocalFrame& frame = d.frame;  // the plants' ENU positions are those a flight computes
  terrain::SeedRegionQuery query;
  query.box = box;
  query.seedLevel = terrain::seedLevelFor(grid, lat, seedOptions.targetAreaM2);
  query.densityM2 = vegetation::densestGroundDensity(d.catalog);
  query.select = terrain::RegionSelect::Overlap;
  const uint64_t maxPlants = options.maxPlants;
  // A cheap bound first (triangles × their flat area × the densest species, no heights): a huge
  // box is refused at once, not after growing it.
  if (Status bounded = checkUpperBound(grid, roots, query, lat, options); !bounded) return bounded.error();

  // The box's finest tiles of both layers in one settle (decoded in parallel); the rest (tiles
  // beside the box that edge triangles reach, ancestors where a tile is missing) on demand.
  SettledTiles tiles(d.source, d.meta);
  prefetchBox(tiles, box, d.meta.maxZoom);
  terrain::ResidentHeights heights(grid, [&](const geo::TileId& t) {
    return tiles.finest({streaming::TileLayer::Height, t});
  });
  const terrain::SeedRegion region = terrain::seedTrianglesIn(grid, roots, frame, heights, query);
  if (tiles.error()) return *tiles.error();

  PlantsInBox out;
  out.datasetName = d.meta.name;
  out.seedLevel = query.seedLevel;
  out.seedTriangles = region.triangles.size();
  out.nodataSkipped = region.nodataSkipped;
  uint64_t count = 0;
  const std::vector<vegetation::CanopyTree> crowns = boxCrowns(options, frame, d.catalog);
  const vegetation::TreeGrid treeGrid = crowns.empty() ? vegetation::TreeGrid{} : vegetation::treeGridFor(d.catalog);
  LandcoverLookup landcover;
  if (d.meta.landcover) {
    landcover.source = d.source.get();
    landcover.masks = landcoverMasks(d.catalog, *d.meta.landcover);
  }
  grow(grid, frame, region, box, d.catalog, vegetation::SeedingOptions{options.clusterSize}, crowns, treeGrid, tiles,
       d.meta.maxZoom, maxPlants, landcover, out, count);
  if (tiles.error()) return *tiles.error();
  if (landcover.error) return *landcover.error;
  if (count > maxPlants) return tooManyPlants(options, "the box grows " + plural(count, "plant"), count);
  return out;
}

}  // namespace vegstream::scene
