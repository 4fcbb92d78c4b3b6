// Landcover classes drive the species (issue 41, item 2), end to end: a small synthetic
// landcover GeoTIFF of WorldCover codes in strips across the Kolob plateau's forest of the Zion
// sample (10 tree cover, 30 grassland, 50 built-up, 80 water, and 7, a code WorldCover lacks) is
// imported with the Zion DEM and imagery; then the trees (scene::treesInBox, what `vegstream
// plants` exports and a flight's tree field places) stand only in tree cover, the plants
// (scene::plantsInBox) are grass and tufts (herbaceous) in grassland and nothing in tree cover (the forest floor grows no
// meadow: vegetation/landcover_species.h), built-up, water or the unknown code; the importer
// warned once about code 7 with its pixel count; the reader gives each strip's class (as `query`
// prints it). A catalog whose table lets built-up grow trees puts them back there: the mask, not
// the colour, keeps them out. Prints the species counts per class.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include "datasets/dataset_reader.h"
#include "datasets/geotiff_import.h"
#include "datasets/progress.h"
#include "scene/plants_in_box.h"
#include "scene/trees_in_box.h"
#include "tests/support/test_dirs.h"

namespace vegstream::scene {
namespace {

namespace fs = std::filesystem;

// The strips, west to east: [west, east) in degrees of longitude, and their WorldCover code.
struct Strip {
  double west, east;
  int code;
  const char* name;
};
constexpr double kWest = -113.09, kEast = -113.06, kSouth = 37.44, kNorth = 37.47, kCell = 1e-4;
const Strip kStrips[] = {{kWest, -113.077, 10, "tree cover"},   {-113.077, -113.075, 30, "grassland"},
                         {-113.075, -113.073, 50, "built-up"},  {-113.073, -113.0715, 80, "water"},
                         {-113.0715, kEast, 7, "unknown code 7"}};
constexpr double kEdgeMarginDeg = 0.0005;  // ~44 m: a landcover pixel of the ground mosaic and more

const Strip* stripOf(double lon) {
  for (const Strip& s : kStrips)
    if (lon >= s.west && lon < s.east) return &s;
  return nullptr;
}
bool nearAnEdge(double lon) {
  for (const Strip& s : kStrips)
    if (std::abs(lon - s.west) < kEdgeMarginDeg || std::abs(lon - s.east) < kEdgeMarginDeg) return true;
  return false;
}

// The landcover raster: an ESRI ASCII grid in EPSG:4326 turned into a GeoTIFF by gdal_translate.
Status writeLandcoverTiff(const fs::path& dir, fs::path& tif) {
  const fs::path asc = dir / "landcover.asc";
  tif = dir / "landcover.tif";
  const int cols = static_cast<int>(std::lround((kEast - kWest) / kCell)),
            rows = static_cast<int>(std::lround((kNorth - kSouth) / kCell));
  std::ofstream out(asc);
  out << "ncols " << cols << "\nnrows " << rows << "\nxllcorner " << kWest << "\nyllcorner " << kSouth
      << "\ncellsize " << kCell << "\nNODATA_value 0\n";
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) out << stripOf(kWest + (c + 0.5) * kCell)->code << (c + 1 < cols ? " " : "\n");
  }
  out.close();
  const std::string cmd = "gdal_translate -q -ot Byte -a_srs EPSG:4326 -a_nodata 0 '" + asc.string() + "' '" +
                          tif.string() + "'";
  if (std::system(cmd.c_str()) != 0) return makeError(ErrorKind::Io, "failed: " + cmd);
  return {};
}

// Zion (DEM, Landsat 4-3-2 as the demo imports it) with the strips as its landcover layer; the
// importer's log in import.log beside it.
Result<fs::path> zionWithLandcover() {
  return testing::cachedFixture("zion-landcover", testing::programKey(), [](const fs::path& dir) -> Status {
    fs::create_directories(dir);
    fs::path tif;
    if (Status s = writeLandcoverTiff(dir, tif); !s) return s;
    const fs::path zion = fs::path(VEGSTREAM_DATASETS_DIR) / "zion";
    datasets::GeoTiffImportOptions o;
    o.dem = {(zion / "srtm.tif").string()};
    o.imagery.bands = {(zion / "landsat_b4.tif").string(), (zion / "landsat_b3.tif").string(),
                       (zion / "landsat_b2.tif").string()};
    o.imagery.radiometry.method = datasets::RadiometryMethod::Reflectance;
    o.imageryDatetime = "2015-08-18T17:58:00Z";
    datasets::GeoTiffImportOptions::Landcover lc;
    lc.file = tif.string();
    o.landcover = lc;
    o.out = dir / "ds";
    o.name = "zion-landcover";
    o.threads = 2;
    std::ostringstream log;
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(log);
    auto logger = std::make_shared<spdlog::logger>("import", sink);
    logger->set_level(spdlog::level::info);
    datasets::NullProgress progress;
    auto meta = datasets::importGeoTiff(o, logger, progress);
    logger->flush();
    std::ofstream(dir / "import.log") << log.str();
    if (!meta) return meta.error();
    return {};
  });
}

class LandcoverSpeciesScene : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto dir = zionWithLandcover();
    ASSERT_TRUE(dir.ok()) << dir.error().message;
    dir_ = *dir;
    dataset_ = (dir_ / "ds").string();
  }
  fs::path dir_;
  std::string dataset_;
};

constexpr double kLat = 37.454;
// The Kolob plateau's forest (tests/scene/trees_in_box_test.cpp): every strip but the last crosses it.
const geo::GeoBounds kForest{-113.080, 37.450, -113.070, 37.458};

TEST_F(LandcoverSpeciesScene, TheImporterWarnsOnceAboutTheUnknownCode) {
  std::ifstream in(dir_ / "import.log");
  std::stringstream text;
  text << in.rdbuf();
  const std::string log = text.str();
  size_t lines = 0;
  for (size_t at = log.find("unknown to worldcover"); at != std::string::npos;
       at = log.find("unknown to worldcover", at + 1))
    ++lines;
  EXPECT_EQ(lines, 1u) << log;
  EXPECT_NE(log.find("class 7: "), std::string::npos) << log;
  EXPECT_NE(log.find("it grows nothing"), std::string::npos) << log;
}

TEST_F(LandcoverSpeciesScene, TheReaderGivesEachStripsClass) {
  auto reader = datasets::DatasetReader::open(dataset_);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  ASSERT_TRUE(reader->meta().landcover.has_value());
  for (const Strip& s : kStrips) {
    const double lon = 0.5 * (s.west + s.east);
    auto code = reader->landcoverAt(kLat, lon);
    ASSERT_TRUE(code.ok()) << code.error().message;
    ASSERT_TRUE(code->has_value()) << s.name;
    EXPECT_EQ(int(**code), s.code) << s.name;
  }
}

TEST_F(LandcoverSpeciesScene, TreesStandOnlyInTreeCover) {
  const vegetation::SpeciesCatalog& catalog = vegetation::defaultSpeciesCatalog();
  const auto trees = treesInBox(dataset_, kForest, catalog, {});
  ASSERT_TRUE(trees.ok()) << trees.error().message;
  std::map<int, std::map<std::string, int>> perClass;
  int inTreeCover = 0, elsewhere = 0;
  for (const BoxTree& t : trees->trees) {
    const Strip* s = stripOf(t.at.lonDeg);
    ASSERT_TRUE(s);
    ++perClass[s->code][catalog.species[t.species].name];
    if (nearAnEdge(t.at.lonDeg)) continue;
    (s->code == 10 ? inTreeCover : elsewhere) += 1;
  }
  std::printf("trees per landcover class in %.3f,%.3f,%.3f,%.3f:\n", kForest.westDeg, kForest.southDeg,
              kForest.eastDeg, kForest.northDeg);
  for (const Strip& s : kStrips) {
    std::printf("  %2d %-15s", s.code, s.name);
    for (const auto& [name, n] : perClass[s.code]) std::printf(" %s %d", name.c_str(), n);
    std::printf("\n");
  }
  EXPECT_GT(inTreeCover, 50);
  EXPECT_EQ(elsewhere, 0);

  // The control: a table that lets built-up grow trees brings them back there.
  nlohmann::json doc = nlohmann::json::parse(vegetation::defaultSpeciesCatalogJson());
  doc["landcover"] = {{"built", {"conifer", "broadleaf", "grass"}}};
  auto builtTrees = vegetation::parseSpeciesCatalog(doc.dump(), "built-trees.json");
  ASSERT_TRUE(builtTrees.ok()) << builtTrees.error().message;
  const auto again = treesInBox(dataset_, kForest, *builtTrees, {});
  ASSERT_TRUE(again.ok()) << again.error().message;
  int inBuilt = 0;
  for (const BoxTree& t : again->trees)
    if (!nearAnEdge(t.at.lonDeg) && stripOf(t.at.lonDeg)->code == 50) ++inBuilt;
  EXPECT_GT(inBuilt, 5);
}

TEST_F(LandcoverSpeciesScene, GrassInGrasslandNothingInTreeCoverBuiltUpWaterOrAnUnknownCode) {
  const vegetation::SpeciesCatalog& catalog = vegetation::defaultSpeciesCatalog();
  constexpr double kHalf = 0.00006;  // ~11 m × 13 m
  std::printf("plants per landcover class (%.0f m boxes at each strip's centre line, lat 37.442 … 37.466):\n",
              2 * kHalf * 88000);
  for (const Strip& s : kStrips) {
    const double lon = 0.5 * (s.west + std::min(s.east, -113.0705));
    std::map<std::string, int> species;
    size_t total = 0;
    for (double lat = 37.442; lat < 37.467; lat += 0.004) {
      const geo::GeoBounds box{lon - kHalf, lat - kHalf, lon + kHalf, lat + kHalf};
      const auto plants = plantsInBox(dataset_, box, catalog, {});
      ASSERT_TRUE(plants.ok()) << plants.error().message;
      total += plants->plants.size();
      for (const BoxPlant& p : plants->plants) {
        const vegetation::Species& sp = catalog.species[p.species];
        ++species[sp.name];
        if (s.code == 30) {  // herbaceous only: grass and the flowers pipeline's dry tufts
          ASSERT_TRUE(sp.kind == vegetation::RendererKind::Grass || sp.kind == vegetation::RendererKind::Flowers)
              << sp.name;
        }
      }
      if (s.code != 30) {
        EXPECT_EQ(plants->plants.size(), 0u) << s.name << " at lat " << lat;
      }
    }
    std::printf("  %2d %-15s %zu plants:", s.code, s.name, total);
    for (const auto& [name, n] : species) std::printf(" %s %d", name.c_str(), n);
    std::printf("\n");
    // Which herb, the colour says (both grow on the plateau's meadows and forest floor).
    if (s.code == 30) {
      EXPECT_GT(total, 5000u);
    }
  }
}

}  // namespace
}  // namespace vegstream::scene
