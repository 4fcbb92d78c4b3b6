// Bad --imagery-nir input, each through the real executable: exit code 2, exactly one line on
// stderr naming the NIR file and the problem, nothing left at or beside --out.

#include <gtest/gtest.h>

#include <fstream>

#include "import_test_util.h"
#include "tests/datasets/tiny_tiff.h"

namespace vegstream::datasets {
namespace {
using namespace vegstream::datasets::test;

const std::string kZion = samples() + "/zion/";
const std::string kWithImagery = "--dem " + kZion + "srtm.tif --imagery-bands " + kZion + "landsat_b4.tif," + kZion +
                                 "landsat_b3.tif," + kZion + "landsat_b2.tif --stretch p1,p99 --max-zoom 10";

// GeoKey directories: WGS 84 / UTM 12N (the Zion Landsat's), WGS 84, and a user-defined
// projected CRS (32767: no EPSG code).
const std::vector<uint16_t> kUtm12Keys = {1, 1, 0, 3, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, 32612};
const std::vector<uint16_t> kWgs84Keys = {1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326};
const std::vector<uint16_t> kUserDefinedKeys = {1, 1, 0, 3, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, 32767};

// A 2×2 UInt16 GeoTIFF of `channels` bands: 30 m pixels at the Zion Landsat's origin (UTM) or
// 10° pixels from (100°E, 50°N) (WGS 84, far from Zion).
fs::path tinyNir(const fs::path& path, const std::vector<uint16_t>& keys, uint16_t channels = 1) {
  TinyImage img;
  img.channels = channels;
  img.pixels = pixelBytes(std::vector<uint16_t>(4 * channels, 12000));
  if (keys == kWgs84Keys)
    img.extra = {doubles(33550, {10, 10, 0}), doubles(33922, {0, 0, 0, 100, 50, 0})};
  else
    img.extra = {doubles(33550, {30, 30, 0}), doubles(33922, {0, 0, 0, 301905, 4154085, 0})};
  img.extra.push_back(shorts(34735, keys));
  writeTinyTiff(path, img);
  return path;
}

ImportRun runImport(const std::string& name, const std::string& args) { return runImportIn("nir_" + name, args); }

TEST(NirBadInput, NirBandBeyondTheFile) {
  // A two-band NIR file: --nir-band chooses (band 1 by default); band 3 does not exist.
  const fs::path p = tinyNir(importTmp("nir_two_src") / "two_bands.tif", kUtm12Keys, 2);
  expectRefused(runImport("two", kWithImagery + " --imagery-nir " + p.string() + " --nir-band 3"), p.string(),
                "band 3 does not exist (the file has 2 bands)");
}

TEST(NirBadInput, NoOverlapWithTheImagery) {
  const fs::path p = tinyNir(importTmp("nir_far_src") / "far.tif", kWgs84Keys);
  const auto c = runImport("far", kWithImagery + " --imagery-nir " + p.string());
  expectRefused(c, p.string(), "do not overlap");
  EXPECT_NE(c.result.err.find("landsat_b4.tif"), std::string::npos) << c.result.err;
}

TEST(NirBadInput, WithoutImagery) {
  const auto c = runImport("alone", "--dem " + kZion + "srtm.tif --imagery-nir " + kZion + "landsat_b5.tif");
  expectRefused(c, kZion + "landsat_b5.tif", "needs imagery");
}

TEST(NirBadInput, NotATiff) {
  const fs::path p = importTmp("nir_text_src") / "nir.tif";
  std::ofstream(p) << "this is a text file, not a TIFF\n";
  expectRefused(runImport("text", kWithImagery + " --imagery-nir " + p.string()), p.string(),
                "not recognized as a supported file format");
}

TEST(NirBadInput, UnknownCrsAsksForNirCrs) {
  const fs::path p = tinyNir(importTmp("nir_crs_src") / "user_crs.tif", kUserDefinedKeys);
  expectRefused(runImport("crs", kWithImagery + " --imagery-nir " + p.string()), p.string(), "--imagery-nir-crs");
}

TEST(NirBadInput, NirCrsWithoutNir) {
  const auto c = runImport("crs_alone", kWithImagery + " --imagery-nir-crs EPSG:32612");
  expectRefused(c, "--imagery-nir-crs", "--imagery-nir FILE");
}

}  // namespace
}  // namespace vegstream::datasets
