// Issue 39 items 4 and 5, through the real executable on lavapipe: straight down from 300 m over
// the Zion sample at the Landsat scene's own time (2015-08-18T17:58:00Z), 320 × 180,
//   - the frame's mean colour over its central half is within CIEDE2000 5 of the ground's own
//     colour there (the bands' surface reflectance, tests/datasets/import/zion_ground_colour.h),
//     up to exposure: the render scaled in linear light to that colour's luminance first;
//   - with plants and trees it is within CIEDE2000 3 of the same view without them (the
//     vegetation keeps the ground's colour from afar: core seed §2.4).
// At the Kolob meadow, a dense Kolob conifer stand and the slickrock east of Springdale.

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "tests/datasets/import/zion_ground_colour.h"
#include "tests/support/ciede2000.h"
#include "tests/support/read_rgb.h"
#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"
#include "tests/support/zion_sample.h"

namespace vegstream {
namespace {
namespace fs = std::filesystem;
using datasets::test::LandsatReflectance;
using datasets::test::LinearRgb;
using datasets::test::Place;

constexpr int kW = 320, kH = 180;
constexpr const char* kAcquisition = "2015-08-18T17:58:00Z";
const Place kPlaces[] = {{"meadow", 37.4815, -113.0095}, {"forest", 37.4940, -113.0080}, {"slickrock", 37.1907, -112.9185}};

double luminance(const std::array<double, 3>& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

// The mean linear colour of the central half of a nadir still at `p`; `extra` options appended.
LinearRgb nadirMean(const fs::path& dataset, const Place& p, const std::string& name, const std::string& extra) {
  const fs::path out = testing::testOutputDir() / (std::string(p.name) + "-" + name + ".png");
  const auto r = testing::runVegstream("snapshot '" + dataset.string() + "' --lat " + std::to_string(p.latDeg) +
                                       " --lon " + std::to_string(p.lonDeg) +
                                       " --alt 300 --heading 0 --pitch -89 --size 320x180 --validate --datetime " +
                                       kAcquisition + " --out '" + out.string() + "' " + extra);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  LinearRgb mean;
  const auto rgb = testing::readRgb8(out, kW, kH);
  if (rgb.empty()) return mean;
  for (int y = kH / 4; y < 3 * kH / 4; ++y)
    for (int x = kW / 4; x < 3 * kW / 4; ++x) {
      for (size_t c = 0; c < 3; ++c) mean.rgb[c] += testing::srgbToLinear(rgb[(size_t(y) * kW + size_t(x)) * 3 + c] / 255.0);
      ++mean.pixels;
    }
  for (double& v : mean.rgb) v /= mean.pixels;
  return mean;
}

// `a` scaled in linear light to the luminance of `reference`, then ΔE00 between them.
double deltaEUpToExposure(LinearRgb a, const LinearRgb& reference) {
  const double k = luminance(reference.rgb) / std::max(luminance(a.rgb), 1e-9);
  for (double& v : a.rgb) v *= k;
  return testing::ciede2000(a.lab(), reference.lab());
}

TEST(GroundColour, NadirFramesKeepTheGroundsColourWithAndWithoutVegetation) {
  const auto dataset = testing::zionSampleDataset();
  ASSERT_TRUE(dataset.ok()) << dataset.error().message;
  const LandsatReflectance bands(std::string(VEGSTREAM_DATASETS_DIR) + "/zion");
  ASSERT_TRUE(bands.ok());
  std::printf("place      ground           render           ΔE00   bare render      ΔE00   render vs bare ΔE00\n");
  for (const Place& p : kPlaces) {
    SCOPED_TRACE(p.name);
    const LinearRgb ground = bands.footprintMean(p);
    ASSERT_GT(ground.pixels, 30);
    const LinearRgb full = nadirMean(*dataset, p, "full", "");
    const LinearRgb bare = nadirMean(*dataset, p, "bare", "--no-plants --trees off");
    const double eFull = deltaEUpToExposure(full, ground), eBare = deltaEUpToExposure(bare, ground);
    const double eVegetation = deltaEUpToExposure(full, bare);
    const auto g = ground.srgb8(), f = full.srgb8(), b = bare.srgb8();
    std::printf("%-10s (%3d,%3d,%3d)  (%3d,%3d,%3d)  %5.2f  (%3d,%3d,%3d)  %5.2f  %5.2f\n", p.name, g[0], g[1], g[2], f[0],
                f[1], f[2], eFull, b[0], b[1], b[2], eBare, eVegetation);
    EXPECT_LT(eFull, 5.0);  // issue 41 item 6: the forest's colour from above within ΔE00 5 of the imagery's
    EXPECT_LT(eBare, 5.0);
    // The plants keep the ground's colour (issue 39). Where the imagery shows closed forest the
    // canopy now closes (issue 41 item 6): the view is crowns, not ground, and only the colour
    // against the imagery (above) applies there.
    if (std::string(p.name) != "forest") {
      EXPECT_LE(eVegetation, 3.0);
    }
  }
}

}  // namespace
}  // namespace vegstream
