// The same tiles imported from every local kind of source give the same dataset as the plain
// directory import (xyz_fixture.h): a TMS-renamed copy read through {-y}, 512-pixel tiles
// stitched from the sample's 256-pixel ones, an MBTiles archive, and PMTiles archives written
// with and without gzip, leaf directories and run lengths.

#include <gtest/gtest.h>

#include "datasets/tile_codec.h"
#include "datasets/tile_template.h"
#include "tests/datasets/xyz/xyz_fixture.h"
#include "tests/support/mbtiles_writer.h"
#include "tests/support/pmtiles_writer.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

TEST_F(XyzSources, TmsRenamedCopyThroughMinusYGivesTheSameTiles) {
  for (const char* layer : {"elevation", "imagery"})
    for (const auto& id : sampleTiles()) {
      const fs::path from = site_ / layer / std::to_string(id.z) / std::to_string(id.x) / (std::to_string(id.y) + ".png");
      writeBytes(work_ / "tms" / layer / std::to_string(id.z) / std::to_string(id.x) /
                     (std::to_string((1 << id.z) - 1 - id.y) + ".png"),
                 bytesOf(from));
    }
  const fs::path out = work_ / "from-tms";
  auto r = import((work_ / "tms/elevation/{z}/{x}/{-y}.png").string(), (work_ / "tms/imagery/{z}/{x}/{-y}.png").string(),
                  out);
  ASSERT_TRUE(r.ok()) << r.error().message;
  expectSameDataset(reference_, out);
  // Read as XYZ rows, the same copy is another place on Earth: the test would notice a mix-up.
  auto wrong = import((work_ / "tms/elevation/{z}/{x}/{y}.png").string(), "", work_ / "wrong");
  ASSERT_TRUE(wrong.ok()) << wrong.error().message;
  EXPECT_NE(wrong->bounds.northDeg, r->bounds.northDeg);
}

// Four 256-pixel tiles of zoom 12 stitched into the one 512-pixel tile of zoom 11 that covers
// them: the import splits it back exactly (lossless PNG), so every tile equals the 256 import.
TEST_F(XyzSources, StitchedTilesOf512PixelsGiveTheSameTiles) {
  const geo::TileId top{11, 379, 804};
  for (const char* layer : {"elevation", "imagery"}) {
    datasets::ColorTile big;
    big.id = top;
    big.size = 512;
    big.rgba.assign(512 * 512 * 4, 0);
    for (const auto& c : geo::children(top)) {
      const fs::path from = site_ / layer / "12" / std::to_string(c.x) / (std::to_string(c.y) + ".png");
      auto t = datasets::readColorTile(from, c, datasets::kTileSize);
      ASSERT_TRUE(t.ok()) << t.error().message;
      ASSERT_EQ(t->size, 256);
      const int ox = (c.x - 2 * top.x) * 256, oy = (c.y - 2 * top.y) * 256;
      for (int y = 0; y < 256; ++y)
        std::copy_n(t->rgba.begin() + y * 256 * 4, 256 * 4, big.rgba.begin() + ((oy + y) * 512 + ox) * 4);
    }
    const fs::path dst = work_ / "big" / layer / "11/379/804.png";
    fs::create_directories(dst.parent_path());
    ASSERT_TRUE(datasets::writeColorTile(dst, big, datasets::ImageryFormat::Png).ok());
  }
  const fs::path out = work_ / "from-512";
  auto r = import((work_ / "big/elevation/{z}/{x}/{y}.png").string(), (work_ / "big/imagery/{z}/{x}/{y}.png").string(),
                  out);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->maxZoom, 12);
  EXPECT_EQ(r->elevationTiles, 5u);
  // The descriptions say "1 tiles at zoom 11 (512 px, split into zoom 12)"; all else is equal.
  expectSameDataset(reference_, out, /*dropSourceDescriptions=*/true);
  EXPECT_NE(r->sources.at(0).description.find("512 px"), std::string::npos) << r->sources.at(0).description;

  // 512-pixel imagery over 256-pixel elevation: read one zoom up, split.
  auto mixed = import(siteTemplate("elevation"), (work_ / "big/imagery/{z}/{x}/{y}.png").string(), work_ / "mixed");
  ASSERT_TRUE(mixed.ok()) << mixed.error().message;
  expectSameDataset(reference_, work_ / "mixed", /*dropSourceDescriptions=*/true);
}

TEST_F(XyzSources, MbtilesGivesTheSameTiles) {
  std::string error;
  ASSERT_TRUE(writeMbtiles(work_ / "elevation.mbtiles", sampleLayer("terrain-rgb"), "png", error)) << error;
  ASSERT_TRUE(writeMbtiles(work_ / "imagery.mbtiles", sampleLayer("map"), "png", error)) << error;
  const fs::path out = work_ / "from-mbtiles";
  auto r = import((work_ / "elevation.mbtiles").string(), (work_ / "imagery.mbtiles").string(), out);
  ASSERT_TRUE(r.ok()) << r.error().message;
  expectSameDataset(reference_, out);
  // The archive's own kind is found from its first bytes too, whatever its name.
  fs::copy_file(work_ / "elevation.mbtiles", work_ / "elevation.db");
  auto sniffed = datasets::openXyzSource((work_ / "elevation.db").string());
  ASSERT_TRUE(sniffed.ok()) << sniffed.error().message;
  EXPECT_STREQ((*sniffed)->kind(), "MBTiles");
  auto ids = (*sniffed)->tilesAt(12, std::nullopt, 100);
  ASSERT_TRUE(ids.ok());
  EXPECT_EQ(*ids, sampleTiles());
}

TEST_F(XyzSources, PmtilesGiveTheSameTilesWithAndWithoutCompressionAndLeaves) {
  struct Variant {
    const char* name;
    PmtilesWriteOptions options;
  };
  const Variant variants[] = {
      {"plain", {}},
      {"gzip-directories-leaves", {.gzipDirectories = true, .maxRootEntries = 1}},
      {"gzip-tiles-leaves-of-3", {.gzipDirectories = false, .gzipTiles = true, .maxRootEntries = 3}},
  };
  for (const Variant& v : variants) {
    SCOPED_TRACE(v.name);
    const fs::path e = work_ / (std::string(v.name) + "-elevation.pmtiles"),
                   i = work_ / (std::string(v.name) + "-imagery.pmtiles");
    writePmtiles(e, sampleLayer("terrain-rgb"), v.options);
    writePmtiles(i, sampleLayer("map"), v.options);
    const fs::path out = work_ / (std::string("from-") + v.name);
    auto r = import(e.string(), i.string(), out);
    ASSERT_TRUE(r.ok()) << r.error().message;
    expectSameDataset(reference_, out);
    // Listing walks the directories (no bounds) and finds the same four tiles.
    auto source = datasets::openXyzSource(e.string());
    ASSERT_TRUE(source.ok()) << source.error().message;
    auto ids = (*source)->tilesAt(12, std::nullopt, 100);
    ASSERT_TRUE(ids.ok()) << ids.error().message;
    EXPECT_EQ(*ids, sampleTiles());
    auto none = (*source)->tilesAt(11, std::nullopt, 100);
    ASSERT_TRUE(none.ok());
    EXPECT_TRUE(none->empty());
  }
}

// One tile's bytes for all four: the writer stores one entry with run length 4 (the 2 × 2 block
// is four consecutive Hilbert ids); every tile of it reads as that tile.
TEST_F(XyzSources, PmtilesRunLengthServesOneTileForSeveral) {
  const auto layer = sampleLayer("terrain-rgb");
  const std::vector<uint8_t>& first = layer.begin()->second;
  std::map<geo::TileId, std::vector<uint8_t>> same;
  for (const auto& id : sampleTiles()) {
    same[id] = first;
    writeBytes(work_ / "same" / std::to_string(id.z) / std::to_string(id.x) / (std::to_string(id.y) + ".png"), first);
  }
  const auto archive = buildPmtiles(same);
  EXPECT_LT(archive.size(), 127 + 40 + first.size() + 20) << "one entry, one copy of the tile";
  writeBytes(work_ / "same.pmtiles", archive);
  auto fromDir = import((work_ / "same/{z}/{x}/{y}.png").string(), "", work_ / "dir");
  auto fromArchive = import((work_ / "same.pmtiles").string(), "", work_ / "archive");
  ASSERT_TRUE(fromDir.ok()) << fromDir.error().message;
  ASSERT_TRUE(fromArchive.ok()) << fromArchive.error().message;
  EXPECT_EQ(fromArchive->elevationTiles, 5u);
  expectSameDataset(work_ / "dir", work_ / "archive");
}

// A directory whose rows are zero-padded is read through the files its listing found; a tile
// named twice ("1608.png" and "01608.png") is refused rather than read from either.
TEST_F(XyzSources, ListedFilesAreReadAsFoundAndDuplicatesRefused) {
  for (const auto& [id, bytes] : sampleLayer("terrain-rgb"))
    writeBytes(work_ / "padded" / std::to_string(id.z) / std::to_string(id.x) / ("0" + std::to_string(id.y) + ".png"),
               bytes);
  auto padded = import((work_ / "padded/{z}/{x}/{y}.png").string(), siteTemplate("imagery"), work_ / "from-padded");
  ASSERT_TRUE(padded.ok()) << padded.error().message;
  expectSameDataset(reference_, work_ / "from-padded");
  writeBytes(work_ / "padded/12/758/1608.png", bytesOf(site_ / "elevation/12/758/1608.png"));
  auto twice = import((work_ / "padded/{z}/{x}/{y}.png").string(), "", work_ / "twice");
  ASSERT_FALSE(twice.ok());
  EXPECT_NE(twice.error().message.find("are both tile 12/758/1608"), std::string::npos) << twice.error().message;
  EXPECT_FALSE(fs::exists(work_ / "twice"));
}

TEST_F(XyzSources, BoundsAndMaxZoomSelectTheTiles) {
  auto o = options(siteTemplate("elevation"), siteTemplate("imagery"), work_ / "one");
  const auto b = geo::tileBoundsLonLat({12, 759, 1609});
  const double dx = 0.25 * (b.eastDeg - b.westDeg), dy = 0.25 * (b.northDeg - b.southDeg);
  o.bounds = geo::GeoBounds{b.westDeg + dx, b.southDeg + dy, b.eastDeg - dx, b.northDeg - dy};
  auto r = datasets::importXyzTiles(o, makeNullLogger());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->elevationTiles, 1u);
  EXPECT_EQ(r->imageryTiles, 1u);
  EXPECT_EQ(bytesOf(work_ / "one/elevation/12/759/1609.png"), bytesOf(reference_ / "elevation/12/759/1609.png"));
  o.bounds.reset();
  o.maxZoom = 11;  // the directory has no tiles there
  o.out = work_ / "none";
  auto none = datasets::importXyzTiles(o, makeNullLogger());
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().message.find("no elevation tiles at zoom 11"), std::string::npos) << none.error().message;
  EXPECT_FALSE(fs::exists(o.out));
}

}  // namespace
}  // namespace vegstream::testing
