// The default catalog, unchanged, on imagery it was not tuned on (issue 41 item 1), through the
// import's colour calibration:
// - Goleta's 3 m aerial photo (the shared sample): the golf course, the park and the tree strip
//   along the creek grow grass or trees, the airport apron, a hangar roof and a taxiway stay
//   bare (regions picked by looking at the photo, in its pixels);
// - a synthetic grey winter orthophoto (bluish-grey light, pasture #595f5d, a pine plantation
//   #5d6a62, roads, snow-dusted roofs, shadows): the pasture and the plantation must not all be
//   bare, as they were before the calibration ("grey rock": zero plants, zero trees).
// The identity calibration ("before") is printed beside each figure.

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "tests/app/calibration_fixture.h"

namespace vegstream::testing {
namespace {

namespace veg = vegstream::vegetation;

std::string goleta(const std::string& f) { return std::string(VEGSTREAM_DATASETS_DIR) + "/goleta/" + f; }

// A square of the photo, in its pixels (512 × 512, 3.0273e-5° each from -119.8337, 34.4448).
struct Region {
  const char* name;
  double x, y, radius;
  bool grows;  // expected: grass or trees (true) or bare (false)
};

struct Tally {
  int growing = 0, samples = 0;
  double share() const { return samples ? double(growing) / samples : 0.0; }
};

// The kinds over a 5 × 5 grid of points in the region.
Tally tally(datasets::DatasetReader& reader, const veg::SpeciesCatalog& catalog, const Region& r, double lon0,
            double lat0, double step) {
  Tally t;
  for (int j = -2; j <= 2; ++j)
    for (int i = -2; i <= 2; ++i) {
      const double px = r.x + 0.5 + i * r.radius / 2.0, py = r.y + 0.5 + j * r.radius / 2.0;
      auto c = reader.colorAt(lat0 - py * step, lon0 + px * step);
      if (!c.ok() || !*c) continue;
      const uint8_t p[3] = {(**c)[0], (**c)[1], (**c)[2]};
      const Kind k = kindAt(catalog, p);
      ++t.samples;
      t.growing += k != Kind::Bare && k != Kind::Gravel ? 1 : 0;
    }
  return t;
}

Result<fs::path> goletaDataset() {
  return cachedFixture("calibration-goleta", vegstreamKey(), [](const fs::path& d) -> Status {
    return importDataset("--dem " + goleta("sba_elev32_wgs84_512x512.tif") + " --dem-crs EPSG:4326 --imagery " +
                             goleta("sba_rgb_wgs84_512x512.tif"),
                         d);
  });
}

TEST(CalibratedSpecies, GoletaGrowsOnItsLawnsAndTreesAndNotOnItsPavement) {
  const auto dataset = goletaDataset();
  ASSERT_TRUE(dataset.ok()) << dataset.error().message;
  auto reader = datasets::DatasetReader::open(*dataset);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  ASSERT_TRUE(reader->meta().colourCalibration.has_value());
  const veg::SpeciesCatalog plain = uncalibratedCatalog(veg::defaultSpeciesCatalog());
  const veg::SpeciesCatalog calibrated = scene::calibratedCatalog(veg::defaultSpeciesCatalog(), reader->meta());
  const Region regions[] = {
      {"golf course", 60, 250, 6, true},   {"park by the freeway", 40, 215, 5, true},
      {"creek tree strip", 120, 430, 3, true}, {"green field", 435, 418, 6, true},
      {"airport apron", 20, 430, 6, false}, {"hangar roof", 53, 437, 5, false},
      {"taxiway", 80, 490, 1.5, false}};
  for (const Region& r : regions) {
    const Tally before = tally(*reader, plain, r, -119.8337, 34.4448, 3.0273437e-5);
    const Tally after = tally(*reader, calibrated, r, -119.8337, 34.4448, 3.0273437e-5);
    std::printf("goleta %-20s growing (grass, flowers, trees): before %2d/%d, after %2d/%d\n", r.name, before.growing,
                before.samples, after.growing, after.samples);
    ASSERT_GT(after.samples, 20) << r.name;
    if (r.grows)
      EXPECT_GE(after.share(), 0.6) << r.name;
    else
      EXPECT_LE(after.share(), 0.4) << r.name;
  }
}

// A flat 256 × 256 px winter scene at 2 m (EPSG:4326, ~0.5 km): pasture on the left half,
// plantation top right, then roads, roofs and shadows; ±3 noise per channel.
TEST(CalibratedSpecies, AGreyWinterOrthophotoStillGrowsItsPastureAndPlantation) {
  const fs::path dir = testOutputDir();
  constexpr int n = 256;
  const double step = 2.0 / 111320.0;
  BandWindow grid{n, n, {}, {-3.0, step, 0.0, 45.0, 0.0, -step}, ""};
  grid.wkt = R"(GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433],AUTHORITY["EPSG","4326"]])";
  std::vector<float> rgb(size_t(n) * n * 3);
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> noise(-3.0f, 3.0f);
  const auto zone = [](int x, int y) {
    if (x < n / 2) return (y % 64) < 4 ? 2 : 0;  // pasture, with a track
    if (y < n / 2) return (x % 32) < 3 ? 4 : 1;  // plantation, with shadowed rows
    if (y < n * 5 / 8) return 2;                 // road
    if (y < n * 7 / 8) return 3;                 // roofs, snow-dusted
    return 4;                                    // shadow
  };
  const float colours[5][3] = {{0x59, 0x5f, 0x5d}, {0x5d, 0x6a, 0x62}, {0x62, 0x68, 0x70}, {0xb8, 0xbe, 0xc8},
                               {0x2c, 0x31, 0x38}};
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      for (int c = 0; c < 3; ++c) rgb[(size_t(y) * n + x) * 3 + c] = colours[zone(x, y)][c] + noise(rng);
  writeRgbTiff(dir / "winter.tif", grid, rgb);
  ASSERT_EQ(runCommand("gdal_calc.py --quiet -A '" + (dir / "winter.tif").string() + "' --A_band 1 --outfile '" +
                       (dir / "dem.tif").string() + "' --type Float32 --calc '300 + 0 * A'")
                .exitCode,
            0);
  ASSERT_TRUE(importDataset("--dem " + (dir / "dem.tif").string() + " --imagery " + (dir / "winter.tif").string(),
                            dir / "winter")
                  .ok());
  auto reader = datasets::DatasetReader::open(dir / "winter");
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  const veg::SpeciesCatalog plain = uncalibratedCatalog(veg::defaultSpeciesCatalog());
  const veg::SpeciesCatalog calibrated = scene::calibratedCatalog(veg::defaultSpeciesCatalog(), reader->meta());
  const Region regions[] = {{"pasture", 64, 96, 40, true}, {"plantation", 190, 64, 40, true}};
  for (const Region& r : regions) {
    const Tally before = tally(*reader, plain, r, -3.0, 45.0, step);
    const Tally after = tally(*reader, calibrated, r, -3.0, 45.0, step);
    std::printf("winter %-10s growing: before %2d/%d, after %2d/%d\n", r.name, before.growing, before.samples,
                after.growing, after.samples);
    ASSERT_GT(after.samples, 20) << r.name;
    EXPECT_GE(after.share(), 0.5) << r.name << ": must not all be bare";
  }
  const Tally road = tally(*reader, calibrated, {"road", 190, 144, 6, false}, -3.0, 45.0, step);
  std::printf("winter road growing after: %d/%d\n", road.growing, road.samples);
}

}  // namespace
}  // namespace vegstream::testing
