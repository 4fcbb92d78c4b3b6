// The GDAL importer on data a GIS user brings (issue 40): CRSs the old table refused, checked
// against GDAL's own bilinear warp; a VRT mosaic and a list of tiles, equal to the whole file;
// an RGB+NIR file's bands chosen; heights in feet. Inputs are made by the tests with GDAL's own
// command-line tools (gdal-bin, from scripts/setup) out of the shared samples.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "datasets/dataset_reader.h"
#include "datasets/landcover.h"
#include "datasets/raster_source.h"
#include "datasets/source_grid.h"
#include "geo/xyz_tiles.h"
#include "geo/crs.h"
#include "geo/projection.h"
#include "tests/datasets/import/dataset_compare.h"
#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;
using testing::runCommand;
using testing::runVegstream;

std::string sample(const std::string& rel) { return std::string(VEGSTREAM_DATASETS_DIR) + "/" + rel; }

void run(const std::string& command) {
  const auto r = runCommand(command);
  ASSERT_EQ(r.exitCode, 0) << command << "\n" << r.err;
}

nlohmann::json gdalinfo(const fs::path& f) {
  const auto r = runCommand("gdalinfo -json '" + f.string() + "'");
  return nlohmann::json::parse(r.out, nullptr, false);
}

struct Agreement {
  double median = 0.0, p90 = 0.0;
  int points = 0;
};

// Heights of the dataset against GDAL's bilinear warp of `source` to EPSG:4326, at the centres
// of that warp's valid pixels (500 picked at random, away from its edges).
Agreement agreementWithGdalWarp(const fs::path& source, const fs::path& dataset, const fs::path& work) {
  const fs::path ref = work / "gdal_bilinear_4326.tif";
  EXPECT_EQ(runCommand("gdalwarp -q -overwrite -t_srs EPSG:4326 -r bilinear -dstnodata -9999 '" + source.string() +
                       "' '" + ref.string() + "'")
                .exitCode,
            0);
  auto r = readWholeRaster(ref.string());
  EXPECT_TRUE(r.ok()) << (r ? "" : r.error().message);
  auto reader = DatasetReader::open(dataset);
  EXPECT_TRUE(reader.ok()) << (reader ? "" : reader.error().message);
  if (!r || !reader) return {};
  std::mt19937 rng(40);
  std::uniform_int_distribution<int> col(4, r->width - 5), row(4, r->height - 5);
  std::vector<double> diffs;
  for (int tries = 0; tries < 20000 && diffs.size() < 500; ++tries) {
    const int i = col(rng), j = row(rng);
    const float want = r->at(i, j);
    if (std::isnan(want)) continue;
    const auto lonLat = r->georef.pixelCentre(i, j);
    auto got = reader->heightAt(lonLat[1], lonLat[0]);
    if (!got || std::isnan(*got)) continue;
    diffs.push_back(std::abs(*got - want));
  }
  std::sort(diffs.begin(), diffs.end());
  Agreement a;
  a.points = static_cast<int>(diffs.size());
  if (!diffs.empty()) {
    a.median = diffs[diffs.size() / 2];
    a.p90 = diffs[diffs.size() * 9 / 10];
  }
  return a;
}

class GdalImport : public ::testing::Test {
 protected:
  void SetUp() override { work_ = testing::testOutputDir(); }
  fs::path work_;
};

TEST_F(GdalImport, Nad83Utm12nAgreesWithGdalWarp) {
  // The CRS of USGS 1 m DEMs and NAIP: the SRTM sample warped into it by GDAL (cubic, 30 m).
  const fs::path src = work_ / "dem_26912.tif";
  run("gdalwarp -q -t_srs EPSG:26912 -tr 30 30 -r cubic '" + sample("zion/srtm.tif") + "' '" + src.string() + "'");
  const fs::path out = work_ / "ds";
  const auto r = runVegstream("import --dem '" + src.string() + "' --max-zoom 14 --out '" + out.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto meta = readDatasetMeta(out);
  ASSERT_TRUE(meta);
  EXPECT_EQ(meta->sources[0].crsCode, "EPSG:26912");
  EXPECT_EQ(meta->sources[0].driver, "GTiff");
  EXPECT_NEAR(meta->sources[0].resolutionM, 30.0, 1.0);
  const Agreement a = agreementWithGdalWarp(src, out, work_);
  std::printf("EPSG:26912: %d points, |vegstream − gdalwarp bilinear| median %.3f m, p90 %.3f m\n", a.points,
              a.median, a.p90);
  EXPECT_GE(a.points, 400);
  EXPECT_LE(a.median, 1.5);
}

TEST_F(GdalImport, BritishNationalGridAgreesWithGdalWarp) {
  // Real relief placed on the British National Grid (OSGB36, a datum PROJ shifts by Helmert to
  // WGS 84): the Zion SRTM in UTM, re-labelled into the Peak District.
  const fs::path utm = work_ / "dem_utm.tif", src = work_ / "dem_27700.tif";
  run("gdalwarp -q -t_srs EPSG:32612 -tr 30 30 -r cubic '" + sample("zion/srtm.tif") + "' '" + utm.string() + "'");
  const auto info = gdalinfo(utm);
  ASSERT_TRUE(info.contains("size"));
  const int w = info["size"][0], h = info["size"][1];
  run("gdal_translate -q -a_srs EPSG:27700 -a_ullr 400000 400000 " + std::to_string(400000 + 30 * w) + " " +
      std::to_string(400000 - 30 * h) + " '" + utm.string() + "' '" + src.string() + "'");
  const fs::path out = work_ / "ds";
  const auto r = runVegstream("import --dem '" + src.string() + "' --max-zoom 14 --out '" + out.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto meta = readDatasetMeta(out);
  ASSERT_TRUE(meta);
  EXPECT_EQ(meta->sources[0].crsCode, "EPSG:27700");
  EXPECT_NE(meta->sources[0].crs.find("British National Grid"), std::string::npos) << meta->sources[0].crs;
  EXPECT_NEAR(meta->bounds.centre().y, 53.3, 0.3);  // the Peak District
  const Agreement a = agreementWithGdalWarp(src, out, work_);
  std::printf("EPSG:27700: %d points, |vegstream − gdalwarp bilinear| median %.3f m, p90 %.3f m\n", a.points,
              a.median, a.p90);
  EXPECT_GE(a.points, 400);
  EXPECT_LE(a.median, 1.5);
}

// The importer projects exactly every 8 tile pixels and interpolates in between (GDAL's
// approximate transformer's trade): within 1/8 source pixel of the exact PROJ position, here for
// British National Grid and NAD83 / UTM rasters at the zoom of their pixels and beyond.
TEST_F(GdalImport, ApproximateTransformIsWithinAnEighthOfAPixel) {
  const fs::path utm = work_ / "dem_26912.tif", bng = work_ / "dem_27700.tif";
  run("gdalwarp -q -t_srs EPSG:26912 -tr 30 30 '" + sample("zion/srtm.tif") + "' '" + utm.string() + "'");
  run("gdal_translate -q -a_srs EPSG:27700 -a_ullr 400000 400000 430000 370000 '" + utm.string() + "' '" +
      bng.string() + "'");
  for (const fs::path& f : {utm, bng}) {
    auto src = RasterSource::open({f.string()}, {});
    ASSERT_TRUE(src.ok()) << src.error().message;
    auto grid = SourceGrid::make(*src);
    ASSERT_TRUE(grid.ok()) << grid.error().message;
    double worst = 0.0;
    for (int z : {12, 14, 16}) {
      const geo::GeoBounds b = grid->extent();
      const geo::TileId id = geo::tileContaining(b.centre(), z);
      const auto approx = grid->tilePixelsToSource(id, 256);
      for (int j = 0; j < 256; j += 3)
        for (int i = 0; i < 256; i += 3) {
          const glm::dvec2 ll = geo::pixelToLonLat(id, {i + 0.5, j + 0.5}, 256);
          auto xy = geo::toProjected(grid->crs(), geo::Geodetic{ll.y, ll.x, 0.0});
          ASSERT_TRUE(xy.ok());
          const glm::dvec2 exact = grid->toPixel(*xy), a = approx[static_cast<size_t>(j * 256 + i)];
          worst = std::max(worst, std::max(std::abs(exact.x - a.x), std::abs(exact.y - a.y)));
        }
    }
    std::printf("%s: worst |approximate − exact| %.2e source pixels (zooms 12, 14, 16)\n", grid->crs().code().c_str(),
                worst);
    EXPECT_LE(worst, 0.125);
  }
}

TEST_F(GdalImport, VrtMosaicAndTileListEqualTheWholeFile) {
  const std::string rgb = sample("goleta/sba_rgb_wgs84_512x512.tif"), dem = sample("goleta/sba_elev32_wgs84_512x512.tif");
  const fs::path left = work_ / "left.tif", right = work_ / "right.tif", vrt = work_ / "mosaic.vrt";
  run("gdal_translate -q -srcwin 0 0 256 512 '" + rgb + "' '" + left.string() + "'");
  run("gdal_translate -q -srcwin 256 0 256 512 '" + rgb + "' '" + right.string() + "'");
  run("gdalbuildvrt -q '" + vrt.string() + "' '" + left.string() + "' '" + right.string() + "'");
  const std::string common = "import --dem '" + dem + "' --dem-crs EPSG:4326 --imagery-format png --out ";
  const fs::path whole = work_ / "whole", viaVrt = work_ / "vrt", viaList = work_ / "list";
  auto r = runVegstream(common + "'" + whole.string() + "' --imagery '" + rgb + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runVegstream(common + "'" + viaVrt.string() + "' --imagery '" + vrt.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runVegstream(common + "'" + viaList.string() + "' --imagery '" + left.string() + "' '" + right.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto a = test::compareTileTrees(whole, viaVrt), b = test::compareTileTrees(whole, viaList);
  EXPECT_GT(a.files, 10);
  EXPECT_EQ(a.different, 0) << a.firstDifference;
  EXPECT_EQ(b.different, 0) << b.firstDifference;
  auto meta = readDatasetMeta(viaVrt);
  ASSERT_TRUE(meta);
  EXPECT_EQ(meta->sources[1].driver, "VRT");
}

TEST_F(GdalImport, FourBandRgbNirFileGivesItsBands) {
  // A NAIP-like file: R, G, B, NIR in one GeoTIFF (the Zion Landsat bands 4, 3, 2, 5). The 4th
  // band is not alpha unless the file says so; --bands and --nir-band choose.
  const std::string z = sample("zion/");
  const fs::path stack = work_ / "stack.vrt", four = work_ / "rgbn.tif";
  run("gdalbuildvrt -q -separate '" + stack.string() + "' " + z + "landsat_b4.tif " + z + "landsat_b3.tif " + z +
      "landsat_b2.tif " + z + "landsat_b5.tif");
  run("gdal_translate -q '" + stack.string() + "' '" + four.string() + "'");
  const std::string common = "import --dem " + z + "srtm.tif --radiometry reflectance --max-zoom 11 --out ";
  const fs::path bands = work_ / "bands", files = work_ / "files";
  auto r = runVegstream(common + "'" + bands.string() + "' --imagery '" + four.string() + "' --bands 1,2,3 --nir-band 4");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runVegstream(common + "'" + files.string() + "' --imagery-bands " + z + "landsat_b4.tif," + z +
                   "landsat_b3.tif," + z + "landsat_b2.tif --imagery-nir " + z + "landsat_b5.tif");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto c = test::compareTileTrees(files, bands);
  EXPECT_GT(c.files, 30);
  EXPECT_EQ(c.different, 0) << c.firstDifference;
  auto meta = readDatasetMeta(bands);
  ASSERT_TRUE(meta);
  EXPECT_TRUE(meta->ndvi);
  EXPECT_GT(meta->ndviTiles, 0u);
  // Without --bands the colour is the first three bands, and the 4th is not taken for alpha
  // (the file does not declare it so): the same imagery tiles, none of them holed.
  const fs::path plain = work_ / "plain";
  r = runVegstream(common + "'" + plain.string() + "' --imagery '" + four.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto i = test::compareTileTrees(bands, plain, "imagery");
  EXPECT_GT(i.files, 10);
  EXPECT_EQ(i.different, 0) << i.firstDifference;
}

TEST_F(GdalImport, HeightsInFeetBecomeMetres) {
  const fs::path feet = work_ / "feet.vrt";
  run("gdal_translate -q -of VRT '" + sample("zion/srtm.tif") + "' '" + feet.string() + "'");
  // Declare the band's unit: the same numbers, now feet.
  std::string xml = testing::readWhole(feet);
  const auto at = xml.find("<NoDataValue>");
  ASSERT_NE(at, std::string::npos);
  xml.insert(at, "<UnitType>ft</UnitType>");
  std::ofstream(feet) << xml;
  const fs::path m = work_ / "metres", f = work_ / "feet";
  auto r = runVegstream("import --dem '" + sample("zion/srtm.tif") + "' --out '" + m.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runVegstream("import --dem '" + feet.string() + "' --out '" + f.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto a = readDatasetMeta(m), b = readDatasetMeta(f);
  ASSERT_TRUE(a && b);
  EXPECT_NEAR(b->maxHeightM, a->maxHeightM * 0.3048, 0.5);
  EXPECT_NEAR(b->minHeightM, a->minHeightM * 0.3048, 0.5);
}

// The same heights in the formats GIS people hold them in: each lossless and keeping the
// geotransform exactly, so each import gives the GeoTIFF's tiles byte for byte. (Text-header
// formats — AAIGrid, EHdr — round the geotransform and so shift the tiles by a hair.)
TEST_F(GdalImport, LosslessFormatsGiveTheGeoTiffsTiles) {
  const std::string srtm = sample("zion/srtm.tif");
  const fs::path ref = work_ / "ref";
  auto r = runVegstream("import --dem '" + srtm + "' --out '" + ref.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  struct Format {
    const char* driver;
    const char* file;
    const char* options;
  };
  for (const Format f : {Format{"HFA", "dem.img", ""}, Format{"JP2OpenJPEG", "dem.jp2", "-co REVERSIBLE=YES -co QUALITY=100"},
                         Format{"ENVI", "dem.envi", ""}}) {
    const fs::path file = work_ / f.file, out = work_ / (std::string("ds_") + f.driver);
    run(std::string("gdal_translate -q -of ") + f.driver + " " + f.options + " '" + srtm + "' '" + file.string() + "'");
    r = runVegstream("import --dem '" + file.string() + "' --out '" + out.string() + "'");
    ASSERT_EQ(r.exitCode, 0) << f.driver << ": " << r.err;
    const auto c = test::compareTileTrees(ref, out);
    std::printf("%s: %d tiles, %d differ from the GeoTIFF import\n", f.driver, c.files, c.different);
    EXPECT_GT(c.files, 20) << f.driver;
    EXPECT_EQ(c.different, 0) << f.driver << ": " << c.firstDifference;
    auto meta = readDatasetMeta(out);
    ASSERT_TRUE(meta);
    EXPECT_EQ(meta->sources[0].driver, f.driver);
  }
}

// When the imagery was taken, as its metadata says (EXIF DateTimeOriginal with its offset, as a
// drone mosaic carries it): recorded as imagery.datetime without --imagery-datetime.
TEST_F(GdalImport, AcquisitionTimeFromTheImagerysMetadata) {
  const fs::path rgb = work_ / "rgb_exif.tif";
  run("gdal_translate -q -mo EXIF_DateTimeOriginal='2021:06:01 10:30:00' -mo EXIF_OffsetTimeOriginal=-07:00 '" +
      sample("goleta/sba_rgb_wgs84_512x512.tif") + "' '" + rgb.string() + "'");
  const fs::path out = work_ / "ds";
  const auto r = runVegstream("import --dem '" + sample("goleta/sba_elev32_wgs84_512x512.tif") +
                              "' --dem-crs EPSG:4326 --imagery '" + rgb.string() + "' --out '" + out.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto meta = readDatasetMeta(out);
  ASSERT_TRUE(meta);
  EXPECT_EQ(meta->imageryDatetime, "2021-06-01T10:30:00-07:00");
  ASSERT_TRUE(meta->radiometry.has_value() && meta->radiometry->deshading.has_value());
  EXPECT_EQ(meta->radiometry->deshading->source, "imagery datetime");
}

// A class raster made from the SRTM heights (WorldCover codes: tree cover above 2000 m, grassland
// below, and an unknown code 7 below 1200 m), imported as the landcover layer: the scheme is
// detected, the unknown code reported once with its count, every tile pixel is one of the
// source's codes (never a blend), and the class at a point is the source's there.
TEST_F(GdalImport, LandcoverLayerKeepsTheClassesAsTheyAre) {
  const fs::path lc = work_ / "landcover.tif";
  run("gdal_calc.py --quiet -A '" + sample("zion/srtm.tif") + "' --outfile '" + lc.string() +
      "' --type Byte --NoDataValue 0 --calc '10*(A>2000)+30*(A<=2000)*(A>1200)+7*(A<=1200)'");
  const fs::path out = work_ / "ds";
  const auto r = runVegstream("import --dem '" + sample("zion/srtm.tif") + "' --landcover '" + lc.string() +
                              "' --max-zoom 13 --out '" + out.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("7"), std::string::npos) << r.err;
  auto meta = readDatasetMeta(out);
  ASSERT_TRUE(meta);
  ASSERT_TRUE(meta->landcover.has_value());
  EXPECT_EQ(*meta->landcover, LandcoverScheme::WorldCover);
  EXPECT_GT(meta->landcoverTiles, 50u);
  // Every pixel of every tile, at every zoom, is a code of the source.
  int tiles = 0;
  for (const auto& e : fs::recursive_directory_iterator(out / "landcover")) {
    if (!e.is_regular_file()) continue;
    const auto rel = fs::relative(e.path(), out / "landcover");
    const geo::TileId id{std::stoi(rel.begin()->string()), std::stoi(std::next(rel.begin())->string()),
                         std::stoi(rel.stem().string())};
    auto t = readLandcoverTile(e.path(), id);
    ASSERT_TRUE(t.ok()) << t.error().message;
    for (const uint8_t c : t->classes) ASSERT_TRUE(c == 0 || c == 7 || c == 10 || c == 30) << int(c) << " in " << rel;
    ++tiles;
  }
  EXPECT_GT(tiles, 50);
  // Where the source is uniform (3 × 3 of one class), the layer has that class.
  auto dem = readWholeRaster(sample("zion/srtm.tif"));
  auto classes = readWholeRaster(lc.string());
  auto reader = DatasetReader::open(out);
  ASSERT_TRUE(dem && classes && reader);
  std::mt19937 rng(41);
  std::uniform_int_distribution<int> col(1, dem->width - 2), row(1, dem->height - 2);
  int checked = 0;
  for (int tries = 0; tries < 20000 && checked < 300; ++tries) {
    const int i = col(rng), j = row(rng);
    const float c = classes->at(i, j);
    bool uniform = !std::isnan(c);
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) uniform = uniform && classes->at(i + di, j + dj) == c;
    if (!uniform) continue;
    const auto lonLat = classes->georef.pixelCentre(i, j);
    const auto got = reader->landcoverAt(lonLat[1], lonLat[0]);
    ASSERT_TRUE(got.ok()) << got.error().message;
    ASSERT_TRUE(got->has_value());
    EXPECT_EQ(static_cast<float>(**got), c) << lonLat[1] << ", " << lonLat[0];
    ++checked;
  }
  EXPECT_EQ(checked, 300);
}

}  // namespace
}  // namespace vegstream::datasets
