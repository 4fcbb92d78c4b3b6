// Species from any imagery without hand tuning (issue 41 item 1): the import's colour calibration
// (datasets/colour_calibration.h) and the excess-green term keep the default catalog's species
// map when the same ground is photographed differently.
//
// Zion's Landsat true colour (bands 4, 3, 2; a 360 × 360 px, 10.8 km sub-area) rendered to 8-bit
// sRGB with the sample's 1st … 99th percentiles (6700 … 18300 DN, one range for all bands): the
// original; then re-stretched (other levels and gamma), desaturated 50 %, shifted blue, shifted
// yellow. Each is imported like any photo (radiometry srgb) and the best species' kind (grass,
// gravel, flowers, tree, bare) compared cell by cell with the original's, through each dataset's
// own calibration ("after") and as before issue 41 ("before": the identity, as datasets imported
// before the calibration read, and no excess-green term). Also: the same import twice gives the same calibration bytes.

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/app/calibration_fixture.h"
#include "tests/support/test_dirs.h"

namespace vegstream::testing {
namespace {

namespace veg = vegstream::vegetation;

constexpr int kX0 = 380, kY0 = 300, kSide = 360;  // the sub-area (Landsat pixels): plateau, canyon, desert
constexpr float kLo = 6700.0f, kHi = 18300.0f;

std::string zion(const std::string& f) { return std::string(VEGSTREAM_DATASETS_DIR) + "/zion/" + f; }

float stretch(float dn, float lo, float hi, float gamma) {
  const float t = std::fmin(std::fmax((dn - lo) / (hi - lo), 0.0f), 1.0f);
  return 255.0f * std::pow(t, gamma);
}

// One rendering of the bands: `pixel` turns the three stretched bytes (0 … 255) into the output.
using Look = std::function<std::array<float, 3>(std::array<float, 3>)>;

std::vector<float> render(const BandWindow& w, float lo, float hi, float gamma, const Look& look) {
  const size_t n = static_cast<size_t>(w.width) * static_cast<size_t>(w.height);
  std::vector<float> out(n * 3);
  for (size_t i = 0; i < n; ++i) {
    std::array<float, 3> c{};
    for (size_t b = 0; b < 3; ++b) c[b] = stretch(w.bands[b][i], lo, hi, gamma);
    c = look(c);
    for (size_t b = 0; b < 3; ++b) out[i * 3 + b] = c[b];
  }
  return out;
}

std::array<float, 3> same(std::array<float, 3> c) { return c; }
std::array<float, 3> desaturated(std::array<float, 3> c) {
  const float y = 0.299f * c[0] + 0.587f * c[1] + 0.114f * c[2];
  return {y + 0.5f * (c[0] - y), y + 0.5f * (c[1] - y), y + 0.5f * (c[2] - y)};
}
std::array<float, 3> blue(std::array<float, 3> c) { return {0.85f * c[0], 0.95f * c[1] + 4.0f, 1.2f * c[2] + 14.0f}; }
std::array<float, 3> yellow(std::array<float, 3> c) { return {1.12f * c[0] + 10.0f, 1.08f * c[1] + 8.0f, 0.8f * c[2]}; }

struct Variant {
  const char* name;
  float lo, hi, gamma;
  Look look;
};

double agreement(const std::vector<int>& a, const std::vector<int>& b) {
  size_t same = 0, n = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
    if (a[i] < 0 || b[i] < 0) continue;
    ++n;
    same += a[i] == b[i] ? 1 : 0;
  }
  return n ? double(same) / double(n) : 0.0;
}

std::string counts(const std::vector<int>& m) {
  int k[5] = {};
  for (int v : m)
    if (v >= 0) ++k[v];
  std::string s;
  for (int i = 0; i < 5; ++i) s += std::string(kKindNames[i]) + " " + std::to_string(k[i]) + (i < 4 ? ", " : "");
  return s;
}

class ZionVariants : public ::testing::Test {
 protected:
  // The renderings and their imports, made once for the test processes (cachedFixture).
  void SetUp() override {
    auto dir = cachedFixture("calibration-zion-variants", vegstreamKey(), [](const fs::path& d) -> Status {
      fs::create_directories(d);
      const BandWindow w = readBands({zion("landsat_b4.tif"), zion("landsat_b3.tif"), zion("landsat_b2.tif")}, kX0,
                                     kY0, kSide, kSide);
      if (w.bands.size() != 3) return makeError(ErrorKind::Internal, "cannot read the Zion bands");
      for (const Variant& v : variants()) {
        const fs::path tif = d / (std::string(v.name) + ".tif");
        writeRgbTiff(tif, w, render(w, v.lo, v.hi, v.gamma, v.look));
        if (Status s = importDataset("--dem " + zion("srtm.tif") + " --imagery " + tif.string(), d / v.name); !s)
          return s;
      }
      return {};
    });
    ASSERT_TRUE(dir.ok()) << dir.error().message;
    dir_ = *dir;
  }
  static std::vector<Variant> variants() {
    return {{"original", kLo, kHi, 1.0f, same},
            {"restretched", 5200.0f, 21000.0f, 0.75f, same},
            {"desaturated", kLo, kHi, 1.0f, desaturated},
            {"blue", kLo, kHi, 1.0f, blue},
            {"yellow", kLo, kHi, 1.0f, yellow}};
  }
  fs::path dataset(const char* name) const { return dir_ / name; }
  fs::path dir_;
};

TEST_F(ZionVariants, KindMapsStayWhenTheImageryIsRestretchedDesaturatedOrCast) {
  auto meta = datasets::readDatasetMeta(dataset("original"));
  ASSERT_TRUE(meta.ok()) << meta.error().message;
  ASSERT_TRUE(meta->colourCalibration.has_value()) << "the importer records the calibration";
  const auto tiles = maxZoomTiles(dataset("original"), meta->maxZoom);
  ASSERT_FALSE(tiles.empty());
  const veg::SpeciesCatalog plain = uncalibratedCatalog(veg::defaultSpeciesCatalog());
  const auto calibrated = [&](const char* name) {
    auto m = datasets::readDatasetMeta(dataset(name));
    EXPECT_TRUE(m.ok());
    return scene::calibratedCatalog(veg::defaultSpeciesCatalog(), *m);
  };
  constexpr int kStep = 8;  // cells of 8 × 8 tile pixels
  const std::vector<int> before0 = kindMap(dataset("original"), plain, tiles, kStep);
  const std::vector<int> after0 = kindMap(dataset("original"), calibrated("original"), tiles, kStep);
  std::printf("original kinds: before (identity) %s; after (calibrated) %s\n", counts(before0).c_str(),
              counts(after0).c_str());
  for (const Variant& v : variants()) {
    if (std::string(v.name) == "original") continue;
    const std::vector<int> before = kindMap(dataset(v.name), plain, tiles, kStep);
    const std::vector<int> after = kindMap(dataset(v.name), calibrated(v.name), tiles, kStep);
    const double b = agreement(before0, before), a = agreement(after0, after);
    std::printf("%-12s cells keeping their kind: before %.1f %%, after %.1f %%   (after: %s)\n", v.name, 100.0 * b,
                100.0 * a, counts(after).c_str());
    EXPECT_GE(a, 0.85) << v.name;
  }
  // The original's calibrated map is not degenerate: it has plants and bare ground.
  int bare = 0, growing = 0;
  for (int k : after0) (k == static_cast<int>(Kind::Bare) ? bare : growing) += k >= 0 ? 1 : 0;
  EXPECT_GT(growing, static_cast<int>(after0.size() / 10));
  EXPECT_GT(bare, static_cast<int>(after0.size() / 10));
}

TEST_F(ZionVariants, TheSameImageryGivesTheSameCalibrationBytes) {
  const fs::path again = testOutputDir() / "original-again";
  ASSERT_TRUE(importDataset("--dem " + zion("srtm.tif") + " --imagery " + (dir_ / "original.tif").string(), again).ok());
  const auto calibrationText = [](const fs::path& d) {
    std::ifstream in(d / "dataset.json");
    const auto j = nlohmann::json::parse(in, nullptr, false);
    return j.is_discarded() ? std::string() : j["imagery"]["colour_calibration"].dump();
  };
  const std::string a = calibrationText(dataset("original")), b = calibrationText(again);
  EXPECT_GT(a.size(), 100u) << a;
  EXPECT_EQ(a, b);
  // And a different look gives a different calibration (the bytes come from the imagery).
  EXPECT_NE(a, calibrationText(dataset("blue")));
}

}  // namespace
}  // namespace vegstream::testing
