// PMTiles v3 units (datasets/pmtiles_format.h) and tile templates (datasets/tile_template.h):
// Hilbert tile ids against the spec's examples and an independent implementation, directories
// and headers round-tripped and refused when damaged.

#include <gtest/gtest.h>

#include "datasets/pmtiles_format.h"
#include "datasets/tile_template.h"
#include "tests/support/pmtiles_writer.h"

namespace vegstream::datasets {
namespace {

TEST(PmtilesTileIds, MatchTheSpecAndAnIndependentImplementation) {
  // The first ids of the spec's reference implementation (zxy_to_tileid).
  EXPECT_EQ(pmtilesTileId({0, 0, 0}), 0u);
  EXPECT_EQ(pmtilesTileId({1, 0, 0}), 1u);
  EXPECT_EQ(pmtilesTileId({1, 0, 1}), 2u);
  EXPECT_EQ(pmtilesTileId({1, 1, 1}), 3u);
  EXPECT_EQ(pmtilesTileId({1, 1, 0}), 4u);
  EXPECT_EQ(pmtilesTileId({2, 0, 0}), 5u);
  EXPECT_EQ(pmtilesFirstId(12), 5592405u);
  // The reference implementation's test (python/test/test_tile.py): 19078479 is 12/3423/1763.
  EXPECT_EQ(pmtilesTileId({12, 3423, 1763}), 19078479u);
  EXPECT_EQ(pmtilesTileZxy(19078479), (geo::TileId{12, 3423, 1763}));
  for (int z = 0; z <= 7; ++z)
    for (int x = 0; x < (1 << z); ++x)
      for (int y = 0; y < (1 << z); ++y) {
        const geo::TileId id{z, x, y};
        const uint64_t t = pmtilesTileId(id);
        ASSERT_EQ(t, testing::referenceTileId(id)) << geo::toString(id);
        ASSERT_EQ(pmtilesTileZxy(t), id) << t;
      }
  for (const geo::TileId id : {geo::TileId{12, 758, 1608}, geo::TileId{20, 123456, 654321}, geo::TileId{30, 1, 1 << 29}})
    EXPECT_EQ(pmtilesTileZxy(pmtilesTileId(id)), id);
  EXPECT_EQ(pmtilesTileId({12, 758, 1608}), testing::referenceTileId({12, 758, 1608}));
}

TEST(PmtilesDirectory, ReadsTheSpecsVarints) {
  // One entry: tile id 624485 (the reference test's varint e5 8e 26), run 1, length 127, offset 0.
  const std::vector<uint8_t> bytes = {0x01, 0xe5, 0x8e, 0x26, 0x01, 0x7f, 0x01};
  auto d = decodePmtilesDirectory(bytes, PmtilesCompression::None, "v");
  ASSERT_TRUE(d.ok()) << d.error().message;
  ASSERT_EQ(d->size(), 1u);
  EXPECT_EQ((*d)[0].tileId, 624485u);
  EXPECT_EQ((*d)[0].length, 127u);
  EXPECT_EQ((*d)[0].offset, 0u);
  EXPECT_EQ(encodePmtilesDirectory(*d), bytes);
}

std::vector<PmtilesEntry> sampleEntries() {
  return {{5, 0, 100, 1}, {6, 100, 50, 3}, {9, 0, 100, 1}, {40, 0, 700, 0}, {100, 1000, 20, 1}};
}

TEST(PmtilesDirectory, RoundTripsPlainAndGzip) {
  const auto entries = sampleEntries();
  const auto plain = encodePmtilesDirectory(entries);
  for (const auto& [bytes, c] : {std::pair{plain, PmtilesCompression::None},
                                 std::pair{testing::gzipBytes(plain), PmtilesCompression::Gzip}}) {
    auto d = decodePmtilesDirectory(bytes, c, "x.pmtiles");
    ASSERT_TRUE(d.ok()) << d.error().message;
    ASSERT_EQ(d->size(), entries.size());
    for (size_t i = 0; i < entries.size(); ++i) {
      EXPECT_EQ((*d)[i].tileId, entries[i].tileId);
      EXPECT_EQ((*d)[i].offset, entries[i].offset);
      EXPECT_EQ((*d)[i].length, entries[i].length);
      EXPECT_EQ((*d)[i].runLength, entries[i].runLength);
    }
  }
  // Lookups: a run covers its ids, a leaf everything up to the next entry, gaps nothing.
  EXPECT_FALSE(findPmtilesEntry(entries, 4));
  EXPECT_EQ(findPmtilesEntry(entries, 8)->tileId, 6u);
  EXPECT_FALSE(findPmtilesEntry(entries, 10));
  EXPECT_EQ(findPmtilesEntry(entries, 99)->tileId, 40u);
  EXPECT_FALSE(findPmtilesEntry(entries, 101));
}

TEST(PmtilesDirectory, DamagedDirectoriesAreRefusedNamingTheArchive) {
  const auto plain = encodePmtilesDirectory(sampleEntries());
  for (size_t cut = 0; cut < plain.size(); ++cut) {
    auto d = decodePmtilesDirectory(std::span(plain).first(cut), PmtilesCompression::None, "cut.pmtiles");
    ASSERT_FALSE(d.ok()) << cut;
    EXPECT_NE(d.error().message.find("cut.pmtiles"), std::string::npos);
  }
  auto trailing = plain;
  trailing.push_back(0);
  EXPECT_FALSE(decodePmtilesDirectory(trailing, PmtilesCompression::None, "t").ok());
  const std::vector<uint8_t> huge = {0xff, 0xff, 0xff, 0xff, 0x0f, 1, 1, 1, 1};  // 4 G entries in 9 bytes
  EXPECT_FALSE(decodePmtilesDirectory(huge, PmtilesCompression::None, "h").ok());
  auto gz = testing::gzipBytes(plain);
  gz.resize(gz.size() - 6);
  EXPECT_FALSE(decodePmtilesDirectory(gz, PmtilesCompression::Gzip, "g").ok());
  EXPECT_EQ(decodePmtilesDirectory(plain, PmtilesCompression::Brotli, "b").error().kind, ErrorKind::Unsupported);
  auto zeroLength = sampleEntries();
  zeroLength[1].length = 0;
  EXPECT_FALSE(decodePmtilesDirectory(encodePmtilesDirectory(zeroLength), PmtilesCompression::None, "z").ok());
}

TEST(PmtilesHeader, RoundTripsAndRefusesDamage) {
  PmtilesHeader h;
  h.rootOffset = 127, h.rootLength = 20, h.tileDataOffset = 200, h.tileDataLength = 1000;
  h.tileType = PmtilesTileType::Png, h.minZoom = 3, h.maxZoom = 12;
  h.minLonE7 = -1124000000, h.minLatE7 = 360000000, h.maxLonE7 = -1122000000, h.maxLatE7 = 362000000;
  const auto bytes = encodePmtilesHeader(h);
  ASSERT_EQ(bytes.size(), kPmtilesHeaderBytes);
  auto back = decodePmtilesHeader(bytes, "a.pmtiles", 1200);
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(back->maxZoom, 12);
  EXPECT_EQ(back->minLonE7, h.minLonE7);
  EXPECT_EQ(back->tileDataLength, 1000u);
  EXPECT_FALSE(decodePmtilesHeader(bytes, "a.pmtiles", 1100).ok()) << "tile data beyond the end";
  EXPECT_FALSE(decodePmtilesHeader(std::span(bytes).first(100), "a.pmtiles").ok());
  auto bad = bytes;
  bad[101] = 2;  // max zoom below min zoom
  EXPECT_FALSE(decodePmtilesHeader(bad, "a.pmtiles").ok());
  bad = bytes;
  bad[99] = 9;  // no such tile type
  EXPECT_FALSE(decodePmtilesHeader(bad, "a.pmtiles").ok());
}

TEST(TileTemplates, ExpandXyzAndTmsRowsAndRefuseOthers) {
  auto t = parseTileTemplate("https://h/t/{z}/{x}/{-y}.png?k=1");
  ASSERT_TRUE(t.ok()) << t.error().message;
  EXPECT_TRUE(t->isUrl);
  EXPECT_TRUE(t->tmsRows);
  EXPECT_EQ(expandTileTemplate(*t, {12, 758, 1608}), "https://h/t/12/758/2487.png?k=1");
  auto xyz = parseTileTemplate("dir/{z}-{y}-{x}.png");
  ASSERT_TRUE(xyz.ok());
  EXPECT_FALSE(xyz->isUrl);
  EXPECT_EQ(expandTileTemplate(*xyz, {3, 1, 2}), "dir/3-2-1.png");
  EXPECT_FALSE(parseTileTemplate("d/{z}/{x}/{y}/{-y}.png").ok());
  EXPECT_FALSE(parseTileTemplate("d/{z}/{x}.png").ok());
  EXPECT_FALSE(parseTileTemplate("d/{z}/{x}/{x}/{y}.png").ok());
  EXPECT_NE(parseTileTemplate("https://{s}.h/{z}/{x}/{y}.png").error().message.find("{s}"), std::string::npos);
  EXPECT_EQ(flipTileRow(flipTileRow(1608, 12), 12), 1608);
}

}  // namespace
}  // namespace vegstream::datasets
