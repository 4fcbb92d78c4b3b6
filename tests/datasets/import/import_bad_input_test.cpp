// Bad input to `vegstream import`, each through the real executable: exit code 2, exactly one
// line on stderr naming the file (or option) and the problem, and nothing left behind — no
// --out, no temporary directory beside it.

#include <gtest/gtest.h>

#include <fstream>

#include "import_test_util.h"
#include "tests/datasets/tiny_tiff.h"

namespace vegstream::datasets {
namespace {
using namespace vegstream::datasets::test;
using vegstream::testing::runVegstream;

const std::string kSrtm = samples() + "/zion/srtm.tif";

// A 2×2 UInt16 GeoTIFF with 10° pixels from (100°E, 50°N) and the given GeoKey directory.
fs::path tinyGeoTiff(const fs::path& path, std::vector<uint16_t> keys, uint32_t claimed = 0) {
  TinyImage img;
  img.pixels = pixelBytes(std::vector<uint16_t>{100, 200, 300, 400});
  img.extra = {doubles(33550, {10, 10, 0}), doubles(33922, {0, 0, 0, 100, 50, 0})};
  if (!keys.empty()) img.extra.push_back(shorts(34735, keys));
  img.claimedWidth = claimed;
  img.claimedHeight = claimed;
  writeTinyTiff(path, img);
  return path;
}
const std::vector<uint16_t> kWgs84Keys = {1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326};

ImportRun runImport(const std::string& name, const std::string& args, const std::string& outName = "out") {
  return runImportIn("bad_" + name, args, outName);
}

TEST(ImportBadInput, MissingFile) {
  const auto c = runImport("missing", "--dem /no/such/dem.tif");
  expectRefused(c, "/no/such/dem.tif", "does not exist");
}

TEST(ImportBadInput, NotATiff) {
  const fs::path p = importTmp("bad_text_src") / "dem.tif";
  std::ofstream(p) << "this is a text file, not a TIFF\n";
  expectRefused(runImport("text", "--dem " + p.string()), p.string(), "not recognized as a supported file format");
}

TEST(ImportBadInput, TruncatedTiff) {
  const fs::path p = importTmp("bad_cut_src") / "srtm_cut.tif";
  fs::copy_file(kSrtm, p);
  fs::resize_file(p, fs::file_size(p) / 2);
  expectRefused(runImport("cut", "--dem " + p.string()), p.string(), "truncated");
}

TEST(ImportBadInput, TiffWithoutGeoreference) {
  const fs::path p = importTmp("bad_plain_src") / "plain.tif";
  TinyImage img;
  img.pixels = pixelBytes(std::vector<uint16_t>{1, 2, 3, 4});
  writeTinyTiff(p, img);
  expectRefused(runImport("plain", "--dem " + p.string()), p.string(), "no georeference");
}

TEST(ImportBadInput, CrsProjDoesNotKnowNamesTheCode) {
  // ProjectedCSType 32767 (user-defined) with no parameters: GDAL reads no CRS from it.
  const fs::path p =
      tinyGeoTiff(importTmp("bad_crs_src") / "odd.tif", {1, 1, 0, 3, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, 32767});
  expectRefused(runImport("crs", "--dem " + p.string()), p.string(), "--dem-crs");
}

TEST(ImportBadInput, DemAndImageryDoNotOverlap) {
  const auto c =
      runImport("overlap", "--dem " + kSrtm + " --imagery " + samples() + "/goleta/sba_rgb_wgs84_512x512.tif");
  expectRefused(c, "srtm.tif", "do not overlap");
  EXPECT_NE(c.result.err.find("sba_rgb_wgs84_512x512.tif"), std::string::npos);
}

TEST(ImportBadInput, HugeHeaderNeverHeldWhole) {
  // Claims 10^12 pixels in a few hundred bytes: refused at open for the strips it lacks.
  const fs::path p = tinyGeoTiff(importTmp("bad_huge_src") / "huge.tif", kWgs84Keys, 1000000);
  expectRefused(runImport("huge", "--dem " + p.string()), p.string(), "lie in blocks the file does not hold");
  // Claims 4 x 10^8 pixels of 10°: opened (GDAL knows only the size), never held whole, and
  // refused for what it claims to cover.
  const fs::path q = tinyGeoTiff(importTmp("bad_large_src") / "large.tif", kWgs84Keys, 20000);
  expectRefused(runImport("large", "--dem " + q.string()), q.string(), "outside the earth");
}

TEST(ImportBadInput, MemoryBudgetTooSmall) {
  expectRefused(runImport("limit", "--dem " + kSrtm + " --memory-mb 10"), "--memory-mb", "at least 64");
}

TEST(ImportBadInput, OutUnderARegularFile) {
  const fs::path parent = importTmp("bad_outfile");
  std::ofstream(parent / "file") << "a regular file";
  ImportRun c;
  c.parent = parent;
  c.result = runVegstream("import --dem " + kSrtm + " --out " + (parent / "file" / "x").string());
  expectRefused(c, (parent / "file" / "x").string(), "is not a directory", 1);
}

TEST(ImportBadInput, OutExistsAndIsNotEmpty) {
  const fs::path parent = importTmp("bad_nonempty");
  fs::create_directories(parent / "out");
  std::ofstream(parent / "out" / "keep.txt") << "mine";
  ImportRun c;
  c.parent = parent;
  c.result = runVegstream("import --dem " + kSrtm + " --out " + (parent / "out").string());
  expectRefused(c, (parent / "out").string(), "not an empty directory", 1);
  EXPECT_EQ(entriesIn(parent / "out"), 1);  // the user's file untouched
}

TEST(ImportBadInput, UnknownStretchAndCrsOptions) {
  expectRefused(runImport("stretch", "--dem " + kSrtm + " --stretch p99,p1"), "--stretch", "p1,p99");
  expectRefused(runImport("demcrs", "--dem " + kSrtm + " --dem-crs EPSG:99999"), "--dem-crs", "99999");
  expectRefused(runImport("bands", "--dem " + kSrtm + " --imagery " + samples() + "/goleta/sba_rgb_wgs84_512x512.tif" +
                                       " --bands 1,2,9"),
                "band 9", "has 3 bands");
}

TEST(ImportBadInput, ImageryBandsOnDifferentGrids) {
  const std::string z = samples() + "/zion/";
  const auto c = runImport("bands", "--dem " + kSrtm + " --imagery-bands " + z + "landsat_b4.tif," + z +
                                        "landsat_b3.tif," + samples() + "/rmnp/rmnp-dem.tif");
  expectRefused(c, "rmnp-dem.tif", "same grid");
}

}  // namespace
}  // namespace vegstream::datasets
