// Canopy height models end to end (issue 41 item 3): a synthetic CHM of 150 known trees
// (tests/support/synthetic_chm.h) written as a UTM GeoTIFF with a flat DEM and forest imagery,
// imported with `vegstream import --canopy-height`, and the trees read back through
// scene::treesInBox — the path of `vegstream plants` — matched against the list (≥ 90 % within
// 1.5 m, heights within 1 m RMS, ≤ 10 % extra). The same trees twice and in a sub-box; outside
// the CHM the trees of a dataset without it; info and query report the layer. Bad CHMs (negative
// heights, centimetres, no overlap) end with one line naming the file, exit 2, no dataset; a
// CHM in declared feet is converted. Inputs are made with GDAL's command-line tools.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "datasets/dataset_format.h"
#include "geo/crs.h"
#include "geo/projection.h"
#include "scene/canopy_trees.h"
#include "scene/tree_field.h"
#include "scene/tree_ground.h"
#include "scene/trees_in_box.h"
#include "streaming/open_tile_source.h"
#include "tests/support/run_command.h"
#include "tests/support/synthetic_chm.h"
#include "tests/support/test_dirs.h"
#include "vegetation/colour_score.h"
#include "vegetation/species_catalog.h"

namespace vegstream::scene {
namespace {
namespace fs = std::filesystem;
using testing::runCommand;
using testing::runVegstream;

// UTM 33N: the DEM and imagery cover [kX0, kX0 + 600] × [kY0, kY0 + 600] m, the CHM the 140 m
// square from (kX0 + kChmOffset, kY0 + kChmOffset).
constexpr double kX0 = 500000.0, kY0 = 5100000.0, kChmOffset = 200.0, kChmSide = 140.0;

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// An ESRI ASCII grid (rows from the north) → a Float32 GeoTIFF in EPSG:32633.
void writeGrid(const fs::path& tif, const std::vector<float>& northFirst, int cols, int rows, double xll, double yll,
               double cell) {
  const fs::path asc = tif.string() + ".asc";
  {
    std::ofstream f(asc);
    f << "ncols " << cols << "\nnrows " << rows << "\nxllcorner " << std::fixed << xll << "\nyllcorner " << yll
      << "\ncellsize " << cell << "\nNODATA_value -9999\n";
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) f << northFirst[size_t(r) * size_t(cols) + size_t(c)] << ' ';
      f << '\n';
    }
  }
  const auto r = runCommand("gdal_translate -q -ot Float32 -a_srs EPSG:32633 " + q(asc) + " " + q(tif));
  ASSERT_EQ(r.exitCode, 0) << r.err;
}

// The synthetic CHM (south-first rows) as a GeoTIFF, values times `scale`.
fs::path writeChm(const fs::path& dir, const std::vector<float>& southFirst, int side, double pixelM, double scale,
                  double x0, double y0, const std::string& name) {
  std::vector<float> north(southFirst.size());
  for (int r = 0; r < side; ++r)
    for (int c = 0; c < side; ++c)
      north[size_t(r) * side + size_t(c)] = float(southFirst[size_t(side - 1 - r) * side + size_t(c)] * scale);
  const fs::path tif = dir / name;
  writeGrid(tif, north, side, side, x0, y0, pixelM);
  return tif;
}

// A tree species' reference colour as sRGB bytes: the imagery of a forest.
std::string forestBurn() {
  const auto& cat = vegetation::defaultSpeciesCatalog();
  for (const auto& s : cat.species)
    if (vegetation::isTree(s)) {
      const glm::vec3 c = vegetation::srgbFromHsv(s.score.reference);
      char b[96];
      std::snprintf(b, sizeof(b), "-burn %d -burn %d -burn %d", int(std::lround(c.r * 255)),
                    int(std::lround(c.g * 255)), int(std::lround(c.b * 255)));
      return b;
    }
  return "";
}

struct Inputs {
  fs::path dem, imagery;
};

Inputs writeGround(const fs::path& dir) {
  Inputs in{dir / "dem.tif", dir / "imagery.tif"};
  char ullr[128];
  std::snprintf(ullr, sizeof(ullr), "-a_ullr %.1f %.1f %.1f %.1f", kX0, kY0 + 600.0, kX0 + 600.0, kY0);
  EXPECT_EQ(runCommand(std::string("gdal_create -q -of GTiff -outsize 60 60 -bands 1 -ot Float32 -burn 500 "
                                   "-a_srs EPSG:32633 ") + ullr + " " + q(in.dem)).exitCode, 0);
  EXPECT_EQ(runCommand("gdal_create -q -of GTiff -outsize 120 120 -bands 3 -ot Byte " + forestBurn() +
                       " -a_srs EPSG:32633 " + ullr + " " + q(in.imagery)).exitCode, 0);
  return in;
}

std::string importArgs(const Inputs& in, const fs::path& out) {
  return "import --dem " + q(in.dem) + " --imagery " + q(in.imagery) + " --deshading off --out " + q(out);
}

geo::GeoBounds lonLatBox(const geo::Crs& utm, double x0, double y0, double x1, double y1) {
  const geo::Geodetic sw = geo::fromProjected(utm, {x0, y0}), ne = geo::fromProjected(utm, {x1, y1});
  const geo::Geodetic nw = geo::fromProjected(utm, {x0, y1}), se = geo::fromProjected(utm, {x1, y0});
  return {std::min(sw.lonDeg, nw.lonDeg), std::min(sw.latDeg, se.latDeg), std::max(ne.lonDeg, se.lonDeg),
          std::max(ne.latDeg, nw.latDeg)};
}

class CanopyImport : public ::testing::Test {
 protected:
  // The synthetic trees in every process (cheap, deterministic); the imports once, shared by the
  // processes ctest runs side by side (testing::cachedFixture: made by one, read by all).
  static void SetUpTestSuite() {
    truth_ = new std::vector<testing::TrueTree>(testing::syntheticTrees(150, kChmSide, 31));
    side_ = static_cast<int>(kChmSide);
  }
  void SetUp() override {
    if (dir_) return;
    auto made = testing::cachedFixture("canopy-trees", testing::vegstreamKey(), [](const fs::path& dir) -> Status {
      fs::create_directories(dir);
      const std::vector<float> chm = testing::rasterizeChm(*truth_, side_, 1.0, 0.15f, 32);
      const Inputs in = writeGround(dir);
      const fs::path tif = writeChm(dir, chm, side_, 1.0, 1.0, kX0 + kChmOffset, kY0 + kChmOffset, "chm.tif");
      const auto with = runVegstream(importArgs(in, dir / "with") + " --canopy-height " + q(tif));
      if (with.exitCode != 0) return makeError(ErrorKind::Internal, "import with the CHM: " + with.err);
      const auto without = runVegstream(importArgs(in, dir / "without"));
      if (without.exitCode != 0) return makeError(ErrorKind::Internal, "import without it: " + without.err);
      return {};
    });
    ASSERT_TRUE(made.ok()) << made.error().message;
    dir_ = new fs::path(*made);
  }
  static void TearDownTestSuite() {
    delete dir_;
    delete truth_;
    dir_ = nullptr;
    truth_ = nullptr;
  }
  static geo::Crs utm() { return *geo::Crs::fromUserInput("EPSG:32633"); }
  static inline fs::path* dir_ = nullptr;
  static inline std::vector<testing::TrueTree>* truth_ = nullptr;
  static inline int side_ = 0;
};

TEST_F(CanopyImport, PlantsFindTheChmTrees) {
  const geo::Crs crs = utm();
  const double cx0 = kX0 + kChmOffset, cy0 = kY0 + kChmOffset;
  const geo::GeoBounds box = lonLatBox(crs, cx0 - 20, cy0 - 20, cx0 + kChmSide + 20, cy0 + kChmSide + 20);
  auto trees = treesInBox((*dir_ / "with").string(), box, vegetation::defaultSpeciesCatalog(), {});
  ASSERT_TRUE(trees) << trees.error().message;
  std::vector<testing::FoundTree> found;
  for (const BoxTree& t : trees->trees) {
    auto xy = geo::toProjected(crs, t.at);
    ASSERT_TRUE(xy);
    const double x = xy->x - cx0, y = xy->y - cy0;
    if (x >= 0 && y >= 0 && x < kChmSide && y < kChmSide) found.push_back({x, y, t.heightM});
  }
  const testing::MatchFigures m = testing::matchTrees(*truth_, found, 1.5);
  std::printf("[ figures  ] import --canopy-height → treesInBox (plants): %d trees, %d found in the CHM, %d matched "
              "within 1.5 m: recall %.1f %%, extra %.1f %%, height RMS %.2f m, position RMS %.2f m\n",
              m.truth, m.found, m.matched, 100.0 * m.recall, 100.0 * m.extraShare, m.heightRmsM, m.positionRmsM);
  EXPECT_GE(m.recall, 0.90);
  EXPECT_LE(m.heightRmsM, 1.0);
  EXPECT_LE(m.extraShare, 0.10);
}

TEST_F(CanopyImport, SameTreesTwiceAndInASubBox) {
  const geo::Crs crs = utm();
  const double cx0 = kX0 + kChmOffset, cy0 = kY0 + kChmOffset;
  const geo::GeoBounds big = lonLatBox(crs, cx0 - 40, cy0 - 40, cx0 + kChmSide + 40, cy0 + kChmSide + 40);
  const geo::GeoBounds small = lonLatBox(crs, cx0 + 30, cy0 + 30, cx0 + 90, cy0 + 90);
  const auto& cat = vegetation::defaultSpeciesCatalog();
  auto a = treesInBox((*dir_ / "with").string(), big, cat, {});
  auto b = treesInBox((*dir_ / "with").string(), big, cat, {});
  auto s = treesInBox((*dir_ / "with").string(), small, cat, {});
  ASSERT_TRUE(a && b && s);
  ASSERT_EQ(a->trees.size(), b->trees.size());
  for (size_t i = 0; i < a->trees.size(); ++i) {
    EXPECT_EQ(a->trees[i].at.lonDeg, b->trees[i].at.lonDeg);
    EXPECT_EQ(a->trees[i].heightM, b->trees[i].heightM);
    EXPECT_EQ(a->trees[i].seed, b->trees[i].seed);
  }
  std::vector<BoxTree> inSmall;
  for (const BoxTree& t : a->trees)
    if (t.at.lonDeg >= small.westDeg && t.at.lonDeg < small.eastDeg && t.at.latDeg >= small.southDeg &&
        t.at.latDeg < small.northDeg)
      inSmall.push_back(t);
  std::printf("[ figures  ] %zu trees in the big box, %zu in the sub-box\n", a->trees.size(), s->trees.size());
  ASSERT_GT(inSmall.size(), 10u);
  ASSERT_EQ(inSmall.size(), s->trees.size());
  for (size_t i = 0; i < inSmall.size(); ++i) {
    EXPECT_EQ(inSmall[i].at.lonDeg, s->trees[i].at.lonDeg);
    EXPECT_EQ(inSmall[i].at.latDeg, s->trees[i].at.latDeg);
    EXPECT_EQ(inSmall[i].heightM, s->trees[i].heightM);
  }
}

// The renderer's tree field places the same CHM trees as `plants` (treesInBox): every tree of
// the CHM's box is drawn by a settled frame above it, at the same place with the same seed.
TEST_F(CanopyImport, TheTreeFieldDrawsThePlantsTrees) {
  const std::string ds = (*dir_ / "with").string();
  auto source = streaming::openTileSource(ds, {});
  ASSERT_TRUE(source);
  auto meta = streaming::readMetaFrom(**source);
  ASSERT_TRUE(meta);
  const geo::GeoBounds& b = meta->bounds;
  const geo::LocalFrame frame({0.5 * (b.southDeg + b.northDeg), b.centre().x, 0.0});  // as scene.cpp
  auto ground = TreeGround::load(**source, *meta, frame, TreeGround::defaultLimits());
  ASSERT_TRUE(ground) << ground.error().message;
  auto canopy = scene::CanopyTrees::load(**source, *meta, frame);
  ASSERT_TRUE(canopy && *canopy);
  const auto& cat = vegetation::defaultSpeciesCatalog();
  std::vector<uint32_t> first(cat.species.size(), UINT32_MAX);
  for (size_t s = 0, next = 0; s < first.size(); ++s)
    if (vegetation::isTree(cat.species[s])) first[s] = static_cast<uint32_t>(next), next += 3;
  TreeFieldOptions o;
  o.lod.horizonM = 400.0f;
  TreeField field(cat, ground->at(), o, first, 3, 4096);
  field.setCanopy(*canopy);
  const double cx0 = kX0 + kChmOffset, cy0 = kY0 + kChmOffset;
  const geo::Geodetic centre = geo::fromProjected(utm(), {cx0 + 70.0, cy0 + 70.0}, 600.0);
  const render::TreeRequest& r = field.prepare(frame.toLocal(centre), true);
  std::vector<render::TreeInstanceGpu> drawn;
  for (const render::TreePageUpload& u : r.uploads) drawn.insert(drawn.end(), u.instances, u.instances + u.count);
  auto box = treesInBox(ds, lonLatBox(utm(), cx0, cy0, cx0 + kChmSide, cy0 + kChmSide), cat, {});
  ASSERT_TRUE(box);
  size_t same = 0;
  for (const BoxTree& t : box->trees) {
    const glm::dvec3 p = frame.toLocal(t.at);
    for (const render::TreeInstanceGpu& g : drawn)
      if (g.seed == t.seed && std::hypot(g.position[0] - p.x, g.position[1] - p.y) < 0.01 && g.heightM == t.heightM) {
        ++same;
        break;
      }
  }
  std::printf("[ figures  ] tree field: %zu trees drawn; %zu of the %zu plants trees in the CHM's box among them\n",
              drawn.size(), same, box->trees.size());
  EXPECT_GT(box->trees.size(), 140u);
  EXPECT_EQ(same, box->trees.size());
}

// Outside the CHM the imagery places the trees as in a dataset without one.
TEST_F(CanopyImport, OutsideTheChmTreesAreAsBefore) {
  const geo::GeoBounds box = lonLatBox(utm(), kX0 + 420, kY0 + 420, kX0 + 560, kY0 + 560);
  const auto& cat = vegetation::defaultSpeciesCatalog();
  auto with = treesInBox((*dir_ / "with").string(), box, cat, {});
  auto without = treesInBox((*dir_ / "without").string(), box, cat, {});
  ASSERT_TRUE(with && without);
  std::printf("[ figures  ] %zu trees outside the CHM (%zu without it)\n", with->trees.size(), without->trees.size());
  ASSERT_GT(without->trees.size(), 20u);
  ASSERT_EQ(with->trees.size(), without->trees.size());
  for (size_t i = 0; i < with->trees.size(); ++i) {
    EXPECT_EQ(with->trees[i].at.lonDeg, without->trees[i].at.lonDeg);
    EXPECT_EQ(with->trees[i].seed, without->trees[i].seed);
    EXPECT_EQ(with->trees[i].heightM, without->trees[i].heightM);
  }
}

// Where the CHM has no data (its west half here), the imagery places the trees as before; its
// east half has the CHM's trees.
TEST_F(CanopyImport, NodataInTheChmKeepsTheImageryTrees) {
  const fs::path work = testing::testOutputDir();
  const std::vector<testing::TrueTree> trees = testing::syntheticTrees(60, kChmSide, 51);
  std::vector<float> chm = testing::rasterizeChm(trees, side_, 1.0, 0.15f, 52);
  for (int r = 0; r < side_; ++r)
    for (int c = 0; c < side_ / 2; ++c) chm[size_t(r) * side_ + size_t(c)] = -9999.0f;  // the grid's nodata
  const double cx0 = kX0 + kChmOffset, cy0 = kY0 + kChmOffset;
  const fs::path tif = writeChm(work, chm, side_, 1.0, 1.0, cx0, cy0, "half.tif");
  const Inputs in{*dir_ / "dem.tif", *dir_ / "imagery.tif"};
  const auto r = runVegstream(importArgs(in, work / "ds") + " --canopy-height " + q(tif));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto& cat = vegetation::defaultSpeciesCatalog();
  const geo::GeoBounds west = lonLatBox(utm(), cx0 + 5, cy0 + 5, cx0 + 60, cy0 + 135);
  auto half = treesInBox((work / "ds").string(), west, cat, {});
  auto without = treesInBox((*dir_ / "without").string(), west, cat, {});
  ASSERT_TRUE(half && without);
  std::printf("[ figures  ] %zu trees under the CHM's nodata half (%zu without a CHM)\n", half->trees.size(),
              without->trees.size());
  ASSERT_GT(without->trees.size(), 10u);
  ASSERT_EQ(half->trees.size(), without->trees.size());
  for (size_t i = 0; i < half->trees.size(); ++i) {
    EXPECT_EQ(half->trees[i].at.lonDeg, without->trees[i].at.lonDeg);
    EXPECT_EQ(half->trees[i].seed, without->trees[i].seed);
  }
  const geo::GeoBounds east = lonLatBox(utm(), cx0 + 75, cy0 + 5, cx0 + 135, cy0 + 135);
  auto chmTrees = treesInBox((work / "ds").string(), east, cat, {});
  ASSERT_TRUE(chmTrees);
  int expected = 0;
  for (const auto& t : trees) expected += t.x >= 75 && t.x < 135 && t.y >= 5 && t.y < 135;
  std::printf("[ figures  ] %zu trees in the CHM's data half, %d true trees there\n", chmTrees->trees.size(), expected);
  EXPECT_NEAR(double(chmTrees->trees.size()), double(expected), 0.1 * expected + 1);
}

TEST_F(CanopyImport, InfoAndQueryReportTheLayer) {
  auto meta = datasets::readDatasetMeta(*dir_ / "with");
  ASSERT_TRUE(meta);
  ASSERT_TRUE(meta->canopyZoom.has_value());
  EXPECT_EQ(*meta->canopyZoom, 17);  // 1 m at 46° N: zoom 17's 0.83 m pixels
  const auto info = runVegstream("info " + q(*dir_ / "with"));
  ASSERT_EQ(info.exitCode, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["tiles"]["canopy"].get<uint64_t>(), meta->canopyTiles);
  EXPECT_EQ(j["tiles"]["on_disk"]["canopy"].get<uint64_t>(), meta->canopyTiles);
  // The tallest tree's top.
  const testing::TrueTree* top = &truth_->front();
  for (const auto& t : *truth_)
    if (t.heightM > top->heightM) top = &t;
  const geo::Geodetic p = geo::fromProjected(utm(), {kX0 + kChmOffset + top->x, kY0 + kChmOffset + top->y});
  char args[96];
  std::snprintf(args, sizeof(args), " --lat %.9f --lon %.9f", p.latDeg, p.lonDeg);
  const auto query = runVegstream("query " + q(*dir_ / "with") + args);
  ASSERT_EQ(query.exitCode, 0) << query.err;
  const auto qj = nlohmann::json::parse(query.out);
  std::printf("[ figures  ] query at the tallest top (%.2f m): canopy_height_m %s\n", top->heightM,
              qj["canopy_height_m"].dump().c_str());
  EXPECT_NEAR(qj["canopy_height_m"].get<double>(), top->heightM, 1.0);
  const auto none = runVegstream("query " + q(*dir_ / "without") + args);
  ASSERT_EQ(none.exitCode, 0) << none.err;
  EXPECT_TRUE(nlohmann::json::parse(none.out)["canopy_height_m"].is_null());
}

// Each bad CHM: exit 2, one line naming the file and the problem, nothing written.
void expectRefused(const Inputs& in, const fs::path& dir, const fs::path& chm, const std::string& problem) {
  const fs::path out = dir / "refused";
  const auto r = runVegstream(importArgs(in, out) + " --canopy-height " + q(chm));
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(testing::countLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(chm.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(problem), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out)) << out;
  std::printf("[ message  ] %s", r.err.c_str());
}

std::vector<float> smallChm(int side, float base) {
  std::vector<float> v(size_t(side) * side, base);
  for (int i = 0; i < side; ++i) v[size_t(i) * side + size_t(i)] = base + 10.0f;
  return v;
}

TEST_F(CanopyImport, BadChmsAreRefused) {
  const fs::path work = testing::testOutputDir();
  const Inputs in{*dir_ / "dem.tif", *dir_ / "imagery.tif"};
  std::vector<float> negative = smallChm(40, 5.0f);
  negative[850] = -7.5f;
  expectRefused(in, work, writeChm(work, negative, 40, 1.0, 1.0, kX0 + 100, kY0 + 100, "negative.tif"), "negative height");
  // Centimetres: a 25 m tree reads 2500.
  expectRefused(in, work, writeChm(work, smallChm(40, 20.0f), 40, 1.0, 100.0, kX0 + 100, kY0 + 100, "centimetres.tif"),
                "centimetres or feet");
  expectRefused(in, work, writeChm(work, smallChm(40, 5.0f), 40, 1.0, 1.0, kX0 + 5000, kY0 + 5000, "elsewhere.tif"),
                "do not overlap");
}

// A CHM whose band declares feet: its heights are converted to metres.
TEST_F(CanopyImport, FeetAreConverted) {
  const fs::path work = testing::testOutputDir();
  const fs::path tif = writeChm(work, smallChm(40, 10.0f), 40, 1.0, 1.0 / 0.3048, kX0 + 100, kY0 + 100, "feet.tif");
  const fs::path vrt = work / "feet.vrt";
  ASSERT_EQ(runCommand("gdal_translate -q -of VRT " + q(tif) + " " + q(vrt)).exitCode, 0);
  {  // the band's unit: feet
    std::ifstream f(vrt);
    std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    const auto at = text.find("<VRTRasterBand");
    ASSERT_NE(at, std::string::npos);
    text.insert(text.find('>', at) + 1, "<UnitType>ft</UnitType>");
    std::ofstream(vrt) << text;
  }
  const Inputs in = writeGround(work);
  const auto r = runVegstream(importArgs(in, work / "ds") + " --canopy-height " + q(vrt));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const geo::Geodetic p = geo::fromProjected(utm(), {kX0 + 100 + 10.5, kY0 + 100 + 40 - 20.5});
  char args[96];
  std::snprintf(args, sizeof(args), " --lat %.9f --lon %.9f", p.latDeg, p.lonDeg);
  const auto query = runVegstream("query " + q(work / "ds") + args);
  ASSERT_EQ(query.exitCode, 0) << query.err;
  const double h = nlohmann::json::parse(query.out)["canopy_height_m"].get<double>();
  std::printf("[ figures  ] 10 m stored as %.2f ft reads %.1f m\n", 10.0 / 0.3048, h);
  EXPECT_NEAR(h, 10.0, 0.3);
}

}  // namespace
}  // namespace vegstream::scene
