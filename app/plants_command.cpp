// `vegstream plants` (plants_command.h): seed triangles of the box at full density → clusters
// and species from the imagery colour → plants, kept where their root lies in the box.

#include "app/plants_command.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <unistd.h>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/exit_codes.h"
#include "core/atomic_file.h"
#include "datasets/dataset_reader.h"
#include "geo/local_frame.h"
#include "terrain/resident_heights.h"
#include "terrain/seed_region.h"
#include "terrain/seed_triangles.h"
#include "vegetation/imagery_texels.h"
#include "vegetation/plant_seeding.h"
#include "vegetation/species_catalog.h"

namespace vegstream::app {
namespace {

namespace fs = std::filesystem;

Error userError(std::string message) { return makeError(ErrorKind::InvalidInput, std::move(message)); }

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, v);
  return buf;
}

Result<geo::GeoBounds> parseBbox(const std::string& text) {
  const std::string prefix = "--bbox " + text + ": ";
  double v[4];
  size_t start = 0;
  for (int i = 0; i < 4; ++i) {
    const size_t end = i < 3 ? text.find(',', start) : text.size();
    if (end == std::string::npos) return userError(prefix + "expected lon0,lat0,lon1,lat1 (four numbers, degrees)");
    const char* first = text.data() + start;
    const char* last = text.data() + end;
    const auto [ptr, ec] = std::from_chars(first, last, v[i]);
    if (ec != std::errc() || ptr != last || !std::isfinite(v[i]))
      return userError(prefix + "expected lon0,lat0,lon1,lat1 (four numbers, degrees); '" + std::string(first, last) +
                       "' is not a number");
    start = end + 1;
  }
  const geo::GeoBounds b{v[0], v[1], v[2], v[3]};
  if (b.westDeg < -180.0 || b.eastDeg > 180.0 || b.southDeg < -85.05 || b.northDeg > 85.05)
    return userError(prefix + "longitudes must be in -180 … 180 and latitudes in -85.05 … 85.05");
  if (b.westDeg >= b.eastDeg) return userError(prefix + "lon0 must be less than lon1");
  if (b.southDeg >= b.northDeg) return userError(prefix + "lat0 must be less than lat1");
  return b;
}

Status checkOutput(const std::string& output) {
  if (output.empty()) return {};
  const fs::path p(output);
  std::error_code ec;
  if (fs::is_directory(p, ec)) return userError("--output " + output + ": is a directory");
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::is_directory(dir, ec)) return userError("--output " + output + ": directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0) return userError("--output " + output + ": directory " + dir.string() + " is not writable");
  return {};
}

// Height tiles from the dataset on demand, for ResidentHeights: the nearest tile at or above
// the one asked for (as a flight's streamer answers), each decoded once and kept.
class DatasetHeights {
 public:
  explicit DatasetHeights(datasets::DatasetReader& reader) : reader_(&reader) {}

  const streaming::ResidentTile* find(const geo::TileId& tile) {
    for (geo::TileId a = tile; a.z >= reader_->meta().minZoom; a = {a.z - 1, a.x >> 1, a.y >> 1}) {
      if (const streaming::ResidentTile* r = load(a)) return r;
      if (a.z == 0) break;
    }
    return nullptr;
  }
  const std::optional<Error>& error() const { return error_; }

 private:
  const streaming::ResidentTile* load(const geo::TileId& id) {
    auto it = tiles_.find(id);
    if (it != tiles_.end()) return it->second.get();
    std::shared_ptr<streaming::ResidentTile> r;
    auto h = reader_->heightTile(id);
    if (!h) {
      if (!error_) error_ = h.error();  // reported after the descent (a callback cannot return it)
    } else if (*h) {
      r = std::make_shared<streaming::ResidentTile>();
      r->key = {streaming::TileLayer::Height, id};
      r->heights = *h;
    }
    return tiles_.emplace(id, r).first->second.get();
  }

  datasets::DatasetReader* reader_;
  std::map<geo::TileId, std::shared_ptr<streaming::ResidentTile>> tiles_;
  std::optional<Error> error_;
};

// Imagery tiles of the finest zoom that has one over a point (the renderer's pieces at full
// detail draw the finest imagery), decoded once.
class DatasetImagery {
 public:
  explicit DatasetImagery(datasets::DatasetReader& reader) : reader_(&reader) {}

  // The tile over the triangle's centroid: the finest that exists at or above maxZoom.
  Result<std::shared_ptr<const datasets::ColorTile>> tileOver(const terrain::BintreeGrid& grid, const terrain::TriCorners& t) {
    const int zMax = reader_->meta().maxZoom;
    const geo::TileId finest = grid.square(t, 2 * (zMax - grid.rootZoom()));
    for (geo::TileId a = finest; a.z >= reader_->meta().minZoom; a = {a.z - 1, a.x >> 1, a.y >> 1}) {
      auto it = tiles_.find(a);
      if (it == tiles_.end()) {
        auto c = reader_->colorTile(a);
        if (!c) return c.error();
        it = tiles_.emplace(a, *c).first;
      }
      if (it->second) return it->second;
      if (a.z == 0) break;
    }
    return std::shared_ptr<const datasets::ColorTile>{};
  }

 private:
  datasets::DatasetReader* reader_;
  std::map<geo::TileId, std::shared_ptr<const datasets::ColorTile>> tiles_;
};

struct PlantRow {
  geo::Geodetic at;
  uint32_t species = 0;
  float heightM = 0.0f, stiffness = 0.0f, sPrime = 0.0f;
};

struct Grown {
  std::vector<PlantRow> rows;  // at most maxPlants kept
  uint64_t count = 0;          // all in the box
};

Result<Grown> growAll(const terrain::BintreeGrid& grid, const geo::LocalFrame& frame, const terrain::SeedRegion& region,
                      const geo::GeoBounds& box, const vegetation::SpeciesCatalog& catalog,
                      const vegetation::SeedingOptions& seeding, DatasetImagery& imagery, uint64_t maxPlants) {
  Grown g;
  std::vector<vegetation::PlantCluster> clusters;
  std::vector<vegetation::Plant> plants;
  for (size_t i = 0; i < region.triangles.size(); ++i) {
    const terrain::RegionSeedTriangle& s = region.triangles[i];
    auto tile = imagery.tileOver(grid, s.corners);
    if (!tile) return tile.error();
    if (!*tile) continue;  // no imagery over it: no colour, no species (as a flight without it)
    const datasets::ColorTile& c = **tile;
    // uv of each vertex in that tile, as StreamedTerrain::seedImagery gives the GPU (float).
    const terrain::GridPoint corners[3] = {s.corners.apex, s.corners.left, s.corners.right};
    glm::vec2 uv[3];
    for (int k = 0; k < 3; ++k)
      uv[k] = glm::vec2(grid.tileXY(corners[k], c.id.z) - glm::dvec2(c.id.x, c.id.y));
    const vegetation::ImageryTexels texels{c.rgba.data(), static_cast<uint32_t>(c.size)};
    const vegetation::BaseColourAt colourAt = [&](glm::vec2 r) {
      return vegetation::sampleImageryLinear(texels, uv[0] + r.x * (uv[1] - uv[0]) + r.y * (uv[2] - uv[0]));
    };
    const vegetation::SeedTriangleInput input{s.key, s.world, s.plantCount};
    clusters.clear();
    plants.clear();
    vegetation::classifyTriangle(input, static_cast<uint32_t>(i), catalog, seeding, colourAt, clusters);
    vegetation::growPlants(input, clusters, catalog, seeding, plants);
    for (const vegetation::Plant& p : plants) {
      const geo::Geodetic at = frame.toGeodetic(p.position);
      if (at.lonDeg < box.westDeg || at.lonDeg >= box.eastDeg || at.latDeg < box.southDeg || at.latDeg >= box.northDeg)
        continue;
      ++g.count;
      if (g.rows.size() < maxPlants) g.rows.push_back({at, p.species, p.heightM, p.stiffness, p.sPrime});
    }
  }
  return g;
}

// One writer for both formats, so CSV and JSON print the same digits.
struct Fields {
  std::string lat, lon, height, plantHeight, stiffness, sPrime;
};
Fields fieldsOf(const PlantRow& r) {
  return {fmt("%.10f", r.at.latDeg),          fmt("%.10f", r.at.lonDeg),
          fmt("%.3f", r.at.heightM),          fmt("%.4f", double(r.heightM)),
          fmt("%.5f", double(r.stiffness)),   fmt("%.5f", double(r.sPrime))};
}

void writeCsv(std::ostream& out, const std::vector<PlantRow>& rows, const vegetation::SpeciesCatalog& catalog) {
  out << "lat,lon,height_m,species,plant_height_m,stiffness,s_prime\n";
  for (const PlantRow& r : rows) {
    const Fields f = fieldsOf(r);
    out << f.lat << ',' << f.lon << ',' << f.height << ',' << catalog.species[r.species].name << ',' << f.plantHeight
        << ',' << f.stiffness << ',' << f.sPrime << '\n';
  }
}

void writeJson(std::ostream& out, const std::vector<PlantRow>& rows, const vegetation::SpeciesCatalog& catalog,
               const std::string& dataset, const std::string& bboxText, int seedLevel, int clusterSize) {
  // Written by hand, one plant per line: nlohmann would print the doubles with 17 digits.
  std::vector<std::string> names;
  for (const vegetation::Species& s : catalog.species) names.push_back(nlohmann::json(s.name).dump());
  out << "{\"dataset\": " << nlohmann::json(dataset).dump() << ",\n \"bbox\": [" << bboxText
      << "],\n \"seed_level\": " << seedLevel << ",\n \"cluster_size\": " << clusterSize
      << ",\n \"plant_count\": " << rows.size() << ",\n \"plants\": [";
  for (size_t i = 0; i < rows.size(); ++i) {
    const Fields f = fieldsOf(rows[i]);
    out << (i ? ",\n  " : "\n  ") << "{\"lat\": " << f.lat << ", \"lon\": " << f.lon << ", \"height_m\": " << f.height
        << ", \"species\": " << names[rows[i].species] << ", \"plant_height_m\": " << f.plantHeight
        << ", \"stiffness\": " << f.stiffness << ", \"s_prime\": " << f.sPrime << "}";
  }
  out << (rows.empty() ? "]}\n" : "\n ]}\n");
}

std::string plural(uint64_t n, const char* what) { return std::to_string(n) + " " + what + (n == 1 ? "" : "s"); }

}  // namespace

CLI::App* addPlantsCommand(CLI::App& cli, PlantsOptions& o) {
  auto* cmd = cli.add_subcommand("plants", "Every plant the full density grows in a lon/lat box, as CSV or JSON");
  cmd->add_option("dataset", o.dataset, "Dataset directory (with imagery: species come from its colour)")->required();
  cmd->add_option("--bbox", o.bbox, "lon0,lat0,lon1,lat1 (WGS 84 degrees)")->required();
  cmd->add_option("--format", o.format, "csv or json")->capture_default_str();
  cmd->add_option("--output", o.output, "File to write (atomically); default: stdout");
  cmd->add_option("--species", o.speciesFile, "Species catalog JSON (default: the embedded config/species.json)");
  cmd->add_option("--cluster-size", o.clusterSize, "Plants per cluster C, 1 … 32")->capture_default_str();
  cmd->add_option("--max-plants", o.maxPlants, "Refuse a box that grows more plants")->capture_default_str();
  return cmd;
}

int runPlants(const PlantsOptions& o, const Logger& log) {
  // Every option first, before any dataset I/O.
  if (o.format != "csv" && o.format != "json")
    return reportError(log, userError("--format " + o.format + ": expected csv or json"));
  if (o.clusterSize < 1 || o.clusterSize > int(vegetation::kMaxClusterSize))
    return reportError(log, userError("--cluster-size " + std::to_string(o.clusterSize) + ": must be 1 … 32"));
  if (o.maxPlants < 1) return reportError(log, userError("--max-plants " + std::to_string(o.maxPlants) + ": must be ≥ 1"));
  auto box = parseBbox(o.bbox);
  if (!box) return reportError(log, box.error());
  const vegetation::SpeciesCatalog* catalog = &vegetation::defaultSpeciesCatalog();
  Result<vegetation::SpeciesCatalog> custom = vegetation::SpeciesCatalog{};
  if (!o.speciesFile.empty()) {
    custom = vegetation::loadSpeciesCatalog(o.speciesFile);
    if (!custom) return reportError(log, custom.error());
    catalog = &*custom;
  }
  if (Status s = checkOutput(o.output); !s) return reportError(log, s.error());

  auto reader = datasets::DatasetReader::open(o.dataset, 16);
  if (!reader) return reportError(log, reader.error());
  const datasets::DatasetMeta& meta = reader->meta();
  if (!meta.imagery)
    return reportError(log, userError("dataset " + o.dataset + " has no imagery: species come from the imagery colour"));
  const geo::GeoBounds& b = meta.bounds;
  if (b.crossesAntimeridian())
    return reportError(log, makeError(ErrorKind::Unsupported, "dataset " + o.dataset + " crosses the antimeridian: not supported"));
  if (box->westDeg < b.westDeg || box->eastDeg > b.eastDeg || box->southDeg < b.southDeg || box->northDeg > b.northDeg)
    return reportError(log, userError("--bbox " + o.bbox + ": not inside the dataset's bounds (lon " + fmt("%.6f", b.westDeg) +
                                      " … " + fmt("%.6f", b.eastDeg) + ", lat " + fmt("%.6f", b.southDeg) + " … " +
                                      fmt("%.6f", b.northDeg) + ")"));

  // The renderer's grid, seed level and roots (StreamedTerrain): the same triangles, keys and
  // vertices as in a flight.
  const terrain::SeedOptions seedOptions;
  const double lat = b.centre().y;
  const terrain::BintreeGrid grid = terrain::gridForSeeds(meta.minZoom, meta.maxZoom, lat, seedOptions.targetAreaM2);
  const geo::TileRange roots = geo::tileRangesCovering(b, meta.minZoom).front();
  // The flight's frame (flight/scene.cpp): the plants' ENU positions are then those a flight
  // computes, bit for bit, not merely the same lat/lon.
  const geo::LocalFrame frame({0.5 * (b.southDeg + b.northDeg), b.centre().x, 0.0});
  terrain::SeedRegionQuery query;
  query.box = *box;
  query.seedLevel = terrain::seedLevelFor(grid, lat, seedOptions.targetAreaM2);
  query.plantCount = static_cast<float>(seedOptions.maxPlants);
  query.select = terrain::RegionSelect::Overlap;
  const auto maxPlants = static_cast<uint64_t>(o.maxPlants);
  auto tooMany = [&](const std::string& howMany, uint64_t n) {
    return reportError(log, userError("--bbox " + o.bbox + ": " + howMany + ", more than --max-plants " +
                                      std::to_string(maxPlants) + "; give a smaller box or --max-plants " +
                                      std::to_string(n)));
  };
  // A cheap bound first (triangles × n_max, no heights): a huge box is refused at once, not
  // after growing it.
  const uint64_t triangles = terrain::countSeedTrianglesIn(grid, roots, query);
  const auto upperBound = static_cast<uint64_t>(double(triangles) * seedOptions.maxPlants);
  if (upperBound > 4 * maxPlants)
    return tooMany("the box grows up to " + plural(upperBound, "plant") + " (" + plural(triangles, "seed triangle") + " × " +
                       std::to_string(int(seedOptions.maxPlants)) + ")",
                   upperBound);

  DatasetHeights tiles(*reader);
  terrain::ResidentHeights heights(grid, [&](const geo::TileId& t) { return tiles.find(t); });
  const terrain::SeedRegion region = terrain::seedTrianglesIn(grid, roots, frame, heights, query);
  if (tiles.error()) return reportError(log, *tiles.error());
  DatasetImagery imagery(*reader);
  const vegetation::SeedingOptions seeding{static_cast<uint32_t>(o.clusterSize)};
  auto grown = growAll(grid, frame, region, *box, *catalog, seeding, imagery, maxPlants);
  if (!grown) return reportError(log, grown.error());
  if (grown->count > maxPlants) return tooMany("the box grows " + plural(grown->count, "plant"), grown->count);
  log->debug("plants: {} seed triangles (level {}), {} skipped for nodata, {} plants", region.triangles.size(),
             query.seedLevel, region.nodataSkipped, grown->count);

  const std::string bboxText = fmt("%.10g", box->westDeg) + ", " + fmt("%.10g", box->southDeg) + ", " +
                               fmt("%.10g", box->eastDeg) + ", " + fmt("%.10g", box->northDeg);
  auto write = [&](std::ostream& out) {
    if (o.format == "csv") writeCsv(out, grown->rows, *catalog);
    else writeJson(out, grown->rows, *catalog, meta.name, bboxText, query.seedLevel, o.clusterSize);
  };
  if (o.output.empty()) {
    write(std::cout);
    std::cout.flush();
    return std::cout ? kExitOk : reportError(log, makeError(ErrorKind::Io, "stdout: write failed"));
  }
  const Status s = writeFileAtomically(o.output, [&](const fs::path& tmp) -> Status {
    std::ofstream f(tmp, std::ios::binary);
    write(f);
    f.close();
    if (!f) return makeError(ErrorKind::Io, "write failed");
    return {};
  });
  if (!s) return reportError(log, userError("--output " + o.output + ": " + s.error().message));
  return kExitOk;
}

}  // namespace vegstream::app
