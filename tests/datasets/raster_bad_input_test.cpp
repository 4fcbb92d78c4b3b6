// RasterSource (GDAL) on files the tests make themselves: bad input must give a clear Error naming the
// file, and the georeference variants (PixelIsPoint, model transformation) must map pixels
// where the GeoTIFF spec says.

#include <cmath>
#include <fstream>

#include <sys/stat.h>

#include <OpenImageIO/imageio.h>
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include "datasets/raster_source.h"
#include "tests/datasets/tiny_tiff.h"
#include "tests/support/test_dirs.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;
using test::TinyImage;

fs::path tmpFile(const std::string& name) {
  const fs::path dir = vegstream::testing::testOutputDir();
  fs::create_directories(dir);
  fs::remove(dir / name);
  return dir / name;
}

// Asserts failure of `kind` whose message names the file and contains `what`.
template <class T>
void expectError(const Result<T>& r, ErrorKind kind, const fs::path& path, const std::string& what) {
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, kind) << r.error().message;
  EXPECT_NE(r.error().message.find(path.string()), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find(what), std::string::npos) << r.error().message;
}

// A 2x2 UInt16 raster, 10° pixels from (100, 50), with WGS 84 keys unless told otherwise.
TinyImage geoImage(uint16_t rasterType = 1) {
  TinyImage img;
  img.pixels = test::pixelBytes(std::vector<uint16_t>{1, 2, 3, 4});
  img.extra = {test::doubles(33550, {10, 10, 0}), test::doubles(33922, {0, 0, 0, 100, 50, 0}),
               test::shorts(34735, {1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, rasterType, 2048, 0, 1, 4326})};
  return img;
}

TEST(GeoTiffBadInput, MissingFileIsNotFound) {
  const fs::path p = tmpFile("does_not_exist.tif");
  expectError(readWholeRaster(fs::path(p).string()), ErrorKind::NotFound, p, "does not exist");
}

TEST(GeoTiffBadInput, FifoAndDirectoryAreRefusedBeforeGdalOpensThem) {
  // A FIFO would block GDAL's open forever; nothing writes to this one.
  const fs::path fifo = tmpFile("pipe.tif");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expectError(readWholeRaster(fifo.string()), ErrorKind::InvalidInput, fifo, "not a regular file");
  const fs::path dir = tmpFile("folder.tif");
  fs::create_directories(dir);
  expectError(readWholeRaster(dir.string()), ErrorKind::InvalidInput, dir, "not a regular file");
}

TEST(GeoTiffBadInput, TextFileNamedTifIsInvalid) {
  const fs::path p = tmpFile("notes.tif");
  std::ofstream(p) << "this is not an image\n";
  expectError(readWholeRaster(fs::path(p).string()), ErrorKind::InvalidInput, p, "not recognized as a supported file format");
}

TEST(GeoTiffBadInput, TruncatedSrtmIsInvalid) {
  const fs::path src = fs::path(VEGSTREAM_DATASETS_DIR) / "zion/srtm.tif";
  const fs::path p = tmpFile("srtm_truncated.tif");
  std::ifstream in(src, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 1000u);
  const auto half = static_cast<std::streamsize>(bytes.size() / 2);
  std::ofstream(p, std::ios::binary).write(bytes.data(), half);
  expectError(readWholeRaster(fs::path(p).string()), ErrorKind::InvalidInput, p, "truncated");
}

TEST(GeoTiffBadInput, PlainTiffHasNoGeoreference) {
  const fs::path p = tmpFile("plain.tif");
  OIIO::ImageSpec spec(4, 3, 1, OIIO::TypeDesc::UINT16);
  std::vector<uint16_t> pixels(12, 7);
  auto out = OIIO::ImageOutput::create(p.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(p.string(), spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT16, pixels.data()));
  ASSERT_TRUE(out->close());
  expectError(readWholeRaster(fs::path(p).string()), ErrorKind::InvalidInput, p, "has no georeference");
}

TEST(GeoTiffBadInput, HugeClaimedSizeNeverAllocatesTheWhole) {
  // A 2x2 image whose header claims 10^12 pixels: 4 TB of float, had anything read it whole. The
  // strips it lacks are far more than a file this size may leave out: refused at open.
  const fs::path p = tmpFile("huge.tif");
  TinyImage img = geoImage();
  img.claimedWidth = 1000000;
  img.claimedHeight = 1000000;
  test::writeTinyTiff(p, img);
  expectError(readWholeRaster(p.string()), ErrorKind::InvalidInput, p, "lie in blocks the file does not hold");
  expectError(RasterSource::open({p.string()}, {}), ErrorKind::InvalidInput, p, "lie in blocks the file does not hold");
  // Claiming 4 x 10^8 pixels (under 1 GiB missing) it opens (GDAL knows only its size), a whole
  // read is refused before allocating, and a window of it is 256 x 256 or fails naming the file.
  const fs::path q = tmpFile("large.tif");
  img.claimedWidth = 20000;
  img.claimedHeight = 20000;
  test::writeTinyTiff(q, img);
  expectError(readWholeRaster(q.string()), ErrorKind::InvalidInput, q, "read window by window");
  auto src = RasterSource::open({q.string()}, {});
  ASSERT_TRUE(src.ok()) << src.error().message;
  EXPECT_EQ(src->width(), 20000);
  auto w = src->read(10000, 10000, 256, 256);
  if (w.ok()) {
    EXPECT_EQ(w->samples.size(), 256u * 256u);
  } else {
    EXPECT_NE(w.error().message.find(q.string()), std::string::npos) << w.error().message;
  }
}

TEST(GeoTiffBadInput, MissingGeoKeysNeedTheUserCrs) {
  const fs::path p = tmpFile("no_keys.tif");
  TinyImage img = geoImage();
  img.extra.pop_back();  // drop the key directory, keep tie point + scale
  test::writeTinyTiff(p, img);
  expectError(readWholeRaster(fs::path(p).string()), ErrorKind::Unsupported, p, "names no CRS; state it with --dem-crs");
  SourceOptions opt;
  opt.assumeCrs = *geo::Crs::fromUserInput("EPSG:4326");
  auto r = readWholeRaster(fs::path(p).string(), opt);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->georef.crs->epsg().value_or(0), 4326);
}

TEST(GeoTiffBadInput, TagPointingPastTheEndIsInvalid) {
  const fs::path p = tmpFile("bad_offset.tif");
  TinyImage img = geoImage();
  test::writeTinyTiff(p, img);
  // Point the ModelTiepoint value (48 bytes, out of line) far past the end of the file.
  std::fstream f(p, std::ios::in | std::ios::out | std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const uint16_t entries = static_cast<uint16_t>(static_cast<uint8_t>(bytes[8]) | static_cast<uint8_t>(bytes[9]) << 8);
  bool patched = false;
  for (uint16_t i = 0; i < entries; ++i) {
    const size_t e = 10 + 12u * i;
    if (static_cast<uint8_t>(bytes[e]) == (33922 & 0xff) && static_cast<uint8_t>(bytes[e + 1]) == (33922 >> 8)) {
      const uint32_t far = 0x7fffff00;
      f.seekp(static_cast<std::streamoff>(e + 8));
      f.write(reinterpret_cast<const char*>(&far), 4);
      patched = true;
    }
  }
  f.close();
  ASSERT_TRUE(patched);
  // GDAL reads no tie point, so no geotransform.
  expectError(readWholeRaster(fs::path(p).string()), ErrorKind::InvalidInput, p, "has no georeference");
}

TEST(GeoTiffBadInput, GroundControlPointsOnlyAreUnsupported) {
  const fs::path p = tmpFile("gcps.tif");
  TinyImage img = geoImage();
  img.extra = {test::doubles(33922, {0, 0, 0, 100, 50, 0, 1, 1, 0, 110, 40, 0}), img.extra[2]};
  test::writeTinyTiff(p, img);
  expectError(readWholeRaster(fs::path(p).string()), ErrorKind::Unsupported, p, "ground control points");
}

TEST(GeoTiffBadInput, NodataThatIsNotANumberIsIgnoredAsGdalDoes) {
  const fs::path p = tmpFile("bad_nodata.tif");
  TinyImage img = geoImage();
  img.extra.push_back(test::ascii(42113, "none"));
  test::writeTinyTiff(p, img);
  auto r = readWholeRaster(p.string());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->samples, (std::vector<float>{1, 2, 3, 4}));
}

TEST(GeoTiffGeoref, PixelIsPointShiftsHalfAPixel) {
  const fs::path p = tmpFile("point.tif");
  test::writeTinyTiff(p, geoImage(2));
  auto r = readWholeRaster(fs::path(p).string());
  ASSERT_TRUE(r.ok()) << r.error().message;
  // The tie point (100, 50) is the first pixel's centre; the corner is half a pixel out.
  EXPECT_DOUBLE_EQ(r->georef.transform[0], 95.0);
  EXPECT_DOUBLE_EQ(r->georef.transform[3], 55.0);
  const auto c = r->georef.pixelCentre(0, 0);
  EXPECT_DOUBLE_EQ(c[0], 100.0);
  EXPECT_DOUBLE_EQ(c[1], 50.0);
}

TEST(GeoTiffGeoref, PixelIsAreaTiePointIsTheCorner) {
  const fs::path p = tmpFile("area.tif");
  test::writeTinyTiff(p, geoImage(1));
  auto r = readWholeRaster(fs::path(p).string());
  ASSERT_TRUE(r.ok()) << r.error().message;
  const auto c = r->georef.pixelCentre(1, 1);
  EXPECT_DOUBLE_EQ(c[0], 115.0);
  EXPECT_DOUBLE_EQ(c[1], 35.0);
  EXPECT_EQ(r->at(1, 1), 4.0f);
}

TEST(GeoTiffGeoref, ModelTransformationWithRotation) {
  const fs::path p = tmpFile("matrix.tif");
  TinyImage img = geoImage();
  // x = 500000 + 2·col + 1·row,  y = 4000000 + 0.5·col − 3·row  (UTM 33N keys).
  img.extra = {test::doubles(34264, {2, 1, 0, 500000, 0.5, -3, 0, 4000000, 0, 0, 1, 0, 0, 0, 0, 1}),
               test::shorts(34735, {1, 1, 0, 2, 1024, 0, 1, 1, 3072, 0, 1, 32633})};
  test::writeTinyTiff(p, img);
  auto r = readWholeRaster(fs::path(p).string());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->georef.crs->epsg().value_or(0), 32633);
  const std::array<double, 6> want{500000, 2, 1, 4000000, 0.5, -3};
  EXPECT_EQ(r->georef.transform, want);
}

TEST(GeoTiffSamplesTypes, Int16KeepsSignAndFloatIsExact) {
  const fs::path p16 = tmpFile("int16.tif");
  TinyImage img = geoImage();
  img.sampleFormat = 2;
  img.pixels = test::pixelBytes(std::vector<int16_t>{-32768, -1, 0, 32767});
  test::writeTinyTiff(p16, img);
  auto r = readWholeRaster(fs::path(p16).string());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->samples, (std::vector<float>{-32768, -1, 0, 32767}));

  const fs::path p32 = tmpFile("float32.tif");
  img.sampleFormat = 3;
  img.bits = 32;
  img.pixels = test::pixelBytes(std::vector<float>{-9999.0f, 2.5f, 20.75f, 1e6f});
  img.extra.push_back(test::ascii(42113, "-9999"));
  test::writeTinyTiff(p32, img);
  r = readWholeRaster(fs::path(p32).string());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_TRUE(std::isnan(r->samples[0]));  // GDAL_NODATA -9999: the mask, read as NaN
  EXPECT_EQ(std::vector<float>(r->samples.begin() + 1, r->samples.end()), (std::vector<float>{2.5f, 20.75f, 1e6f}));
  EXPECT_TRUE(r->isNodata(r->at(0, 0)));
  EXPECT_FALSE(r->isNodata(r->at(1, 0)));
}

TEST(GeoTiffSamplesTypes, UInt8IsNotNormalised) {
  const fs::path p = tmpFile("uint8.tif");
  TinyImage img = geoImage();
  img.bits = 8;
  img.pixels = {0, 1, 200, 255};
  test::writeTinyTiff(p, img);
  auto r = readWholeRaster(fs::path(p).string());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->samples, (std::vector<float>{0, 1, 200, 255}));
}

// A GeoTIFF made by GDAL itself: `bands` bands of `w` × `h` Byte pixels, `options` its creation
// options (sparse: nothing written, so a huge raster costs a few bytes of file).
fs::path gdalTiff(const std::string& name, int w, int h, int bands, std::vector<std::string> options) {
  GDALAllRegister();
  const fs::path p = tmpFile(name);
  options.push_back("SPARSE_OK=TRUE");
  std::vector<const char*> opts;
  for (const std::string& o : options) opts.push_back(o.c_str());
  opts.push_back(nullptr);
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  GDALDataset* d = gtiff->Create(p.string().c_str(), w, h, bands, GDT_Byte, const_cast<char**>(opts.data()));
  EXPECT_NE(d, nullptr);
  GDALClose(d);
  return p;
}

// The ceilings checked at open, before GDAL reads anything (issue 42 item 1, the fuzzer's
// findings in fuzz/regressions/raster_source/): more bands than a source may take, and a block
// (here one tile over a sparse 20 000² raster, 381 MiB) larger than a block may hold.
TEST(GeoTiffBadInput, TooManyBandsOrTooLargeABlockIsRefusedAtOpen) {
  const fs::path many = gdalTiff("seventy_bands.tif", 4, 4, 70, {});
  SourceOptions options;
  auto r = RasterSource::open({many.string()}, options);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(r.error().message.find(many.string()), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("70 bands"), std::string::npos) << r.error().message;
  options.bands = {1, 2, 3};  // three of them are fine (the georeference is what is missing then)
  auto three = RasterSource::open({many.string()}, options);
  ASSERT_FALSE(three.ok());
  EXPECT_EQ(three.error().message.find("bands, more than"), std::string::npos) << three.error().message;

  // One tile: GDAL reads a strip, even a compressed one, in pieces of its own, a tile whole.
  const fs::path strip =
      gdalTiff("one_huge_tile.tif", 20000, 20000, 1, {"TILED=YES", "BLOCKXSIZE=20000", "BLOCKYSIZE=20000"});
  auto big = RasterSource::open({strip.string()}, SourceOptions{});
  ASSERT_FALSE(big.ok());
  EXPECT_EQ(big.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(big.error().message.find("20000 x 20000 pixels (381 MiB)"), std::string::npos) << big.error().message;
  const fs::path tiled = gdalTiff("tiled.tif", 20000, 20000, 1, {"TILED=YES"});
  auto ok = RasterSource::open({tiled.string()}, SourceOptions{});
  ASSERT_FALSE(ok.ok());  // no georeference: refused for that, after the ceilings let it through
  EXPECT_NE(ok.error().message.find("no georeference"), std::string::npos) << ok.error().message;
}

// Blocks a file names but does not hold are zero-filled by GDAL on every read: a sparse file may
// leave out at most 1 GiB plus 64 x its own size (fuzz/regressions/raster_source/
// timeout-16387x50331904-in-48MB-strips.tif claimed 3.3 TB in 410 bytes).
TEST(GeoTiffBadInput, ASparseFileClaimingMoreThanItHoldsIsRefusedAtOpen) {
  const fs::path sparse = gdalTiff("sparse_40000.tif", 40000, 40000, 1, {"TILED=YES"});
  ASSERT_LT(fs::file_size(sparse), 1u << 20);
  auto r = RasterSource::open({sparse.string()}, SourceOptions{});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(r.error().message.find(sparse.string() + ": 1525 MiB of its 40000 x 40000 pixels lie in blocks the file "
                                                     "does not hold"),
            std::string::npos)
      << r.error().message;
  // A sparse file within the ceiling opens (and is refused later for its missing georeference).
  const fs::path small = gdalTiff("sparse_20000.tif", 20000, 20000, 1, {"TILED=YES"});
  auto ok = RasterSource::open({small.string()}, SourceOptions{});
  ASSERT_FALSE(ok.ok());
  EXPECT_NE(ok.error().message.find("no georeference"), std::string::npos) << ok.error().message;
}

}  // namespace
}  // namespace vegstream::datasets
