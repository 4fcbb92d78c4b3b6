// Issue 41 item 6, through the real executable on lavapipe: where the imagery shows closed forest
// the canopy closes. Straight down from 300 m over a Kolob conifer stand of the Zion sample
// (320 × 180, validation on), the share of the view that is not tree — the coverage AOV where the
// species AOV is not a tree species — is within 0.15 of 1 − the imagery's canopy cover, the mean
// of `query`'s canopy_cover over a 5 × 9 grid on the same footprint (30 m Landsat pixels). With --tree-detail 2: in a
// 180-line frame impostors end where a tree is about 5 pixels in size (render/tree_layout.h), which
// straight down from 300 m leaves out every tree under about 9 m, the terrain's imagery colour
// standing in for them; at 2 the trees are drawn as a 360-line frame draws them.
// bench/canopy-closure is the same measure at 640 × 360. Before crowns were sized by their area seen
// from above (vegetation/crown_projection.h) the trees covered 0.76 of the view against 0.98.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/read_rgb.h"
#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"
#include "tests/support/zion_sample.h"
#include "vegetation/species_catalog.h"

namespace vegstream {
namespace {
namespace fs = std::filesystem;

constexpr int kW = 320, kH = 180;
constexpr double kLat = 37.4603, kLon = -113.0254, kAltM = 300.0, kVerticalFovDeg = 55.0;

// The share of the still that trees cover (AOV species k + 1 is catalog species k).
double treeCover(const fs::path& dataset) {
  const fs::path out = testing::testOutputDir() / "canopy-nadir.png";
  const auto r = testing::runVegstream("snapshot '" + dataset.string() + "' --lat " + std::to_string(kLat) + " --lon " +
                                       std::to_string(kLon) +
                                       " --alt 300 --heading 0 --pitch -89 --size 320x180 --validate "
                                       "--tree-detail 2 --aov species,coverage --out '" +
                                       out.string() + "'");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
  const auto coverage = testing::readFloat1(out.parent_path() / "canopy-nadir.coverage.tif", kW, kH);
  const auto species = testing::readFloat1(out.parent_path() / "canopy-nadir.species.tif", kW, kH);
  if (coverage.size() != size_t{kW} * kH || species.size() != coverage.size()) return NAN;
  const auto& catalog = vegetation::defaultSpeciesCatalog().species;
  double sum = 0.0;
  for (size_t i = 0; i < coverage.size(); ++i) {
    const long k = std::lround(species[i]) - 1;
    if (k >= 0 && size_t(k) < catalog.size() && vegetation::isTree(catalog[size_t(k)])) sum += coverage[i];
  }
  return sum / double(coverage.size());
}

// query's canopy_cover averaged over a 5 × 9 grid spanning 90 % of the still's footprint.
double imageryCover(const fs::path& dataset) {
  const double halfH = kAltM * std::tan(kVerticalFovDeg * M_PI / 360.0) * 0.9, halfW = halfH * kW / kH;
  double sum = 0.0;
  int n = 0;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 9; ++i) {
      const double north = (j / 4.0 - 0.5) * 2.0 * halfH, east = (i / 8.0 - 0.5) * 2.0 * halfW;
      const double lat = kLat + north / 111320.0, lon = kLon + east / (111320.0 * std::cos(kLat * M_PI / 180.0));
      const auto q = testing::runVegstream("query '" + dataset.string() + "' --lat " + std::to_string(lat) + " --lon " +
                                           std::to_string(lon));
      EXPECT_EQ(q.exitCode, 0) << q.err;
      if (q.exitCode != 0) continue;
      sum += nlohmann::json::parse(q.out).at("canopy_cover").get<double>();
      ++n;
    }
  return n ? sum / n : NAN;
}

TEST(CanopyClosure, ClosedForestHidesTheGroundFromAbove) {
  const auto dataset = testing::zionSampleDataset();
  ASSERT_TRUE(dataset.ok()) << dataset.error().message;
  const double trees = treeCover(*dataset), cover = imageryCover(*dataset);
  std::printf("trees cover %.3f of the view (visible ground %.3f); imagery canopy cover %.3f (1 - cover %.3f)\n", trees,
              1.0 - trees, cover, 1.0 - cover);
  EXPECT_GT(cover, 0.9) << "the place is no longer closed forest in the imagery: the test measures nothing";
  EXPECT_LE(std::abs((1.0 - trees) - (1.0 - cover)), 0.15);
}

}  // namespace
}  // namespace vegstream
