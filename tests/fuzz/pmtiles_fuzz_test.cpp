// Mutation test of the PMTiles v3 reader (datasets/pmtiles_format.h, the PMTiles source of
// datasets/xyz_source.h) — what `vegstream import` runs on an archive from disk or from any
// server. Small valid inputs (a directory of runs, leaves and shared offsets, plain and gzip; a
// whole archive with leaf directories) are fed mutated (binary_mutations.h): every call must
// return a value or a user error naming the archive — never throw, crash, or print.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "datasets/pmtiles_format.h"
#include "datasets/xyz_source.h"
#include "tests/fuzz/binary_mutations.h"
#include "tests/fuzz/fuzz_support.h"
#include "tests/support/pmtiles_writer.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;
using datasets::PmtilesCompression;

constexpr uint64_t kSeed = 40;  // issue 40
constexpr int kMutations = 1500;

std::vector<datasets::PmtilesEntry> entries() {
  std::vector<datasets::PmtilesEntry> e;
  uint64_t offset = 0;
  for (uint64_t id = 5; id < 200; id += 7) {
    const uint32_t run = id % 3 == 0 ? 3 : 1, length = static_cast<uint32_t>(50 + id % 40);
    e.push_back({id, id % 5 == 0 ? 0 : offset, length, id % 11 == 0 ? 0u : run});
    offset += length;
  }
  return e;
}

template <typename Decode>
void fuzzDirectory(const std::vector<uint8_t>& valid, PmtilesCompression c, const char* what, Decode&& decode) {
  ASSERT_TRUE(decode(valid, c).ok()) << what << ": the unmutated directory must decode";
  Outcomes tally;
  StderrCapture printed(ownTestDir() / "stderr.txt");
  for (int i = 0; i < kMutations; ++i) {
    const ByteMutation m = mutateBytes(valid, kSeed, static_cast<uint64_t>(i));
    expectValueOrError([&] { return decode(m.bytes, c); }, std::string(what) + " " + std::to_string(i) + ": " + m.what,
                       tally);
  }
  const std::string noise = printed.text();
  EXPECT_TRUE(noise.empty()) << noise.substr(0, 2000);
  std::printf("%s: %d mutations, %d decoded, %d refused, %d threw\n", what, kMutations, tally.ok, tally.refused,
              tally.threw);
  EXPECT_EQ(tally.threw, 0);
  EXPECT_GT(tally.refused, kMutations / 10) << "many mutations must break the directory";
}

TEST(PmtilesFuzz, Directories) {
  const auto plain = datasets::encodePmtilesDirectory(entries());
  const auto decode = [](const std::vector<uint8_t>& b, PmtilesCompression c) {
    auto r = datasets::decodePmtilesDirectory(b, c, "fuzz.pmtiles", 4096);
    if (r.ok()) {
      EXPECT_FALSE(r->empty());
      for (size_t i = 1; i < r->size(); ++i) EXPECT_LT((*r)[i - 1].tileId, (*r)[i].tileId);
    } else {
      EXPECT_NE(r.error().message.find("fuzz.pmtiles"), std::string::npos) << r.error().message;
    }
    return r;
  };
  fuzzDirectory(plain, PmtilesCompression::None, "directory (plain)", decode);
  fuzzDirectory(gzipBytes(plain), PmtilesCompression::Gzip, "directory (gzip)", decode);
}

TEST(PmtilesFuzz, Headers) {
  std::map<geo::TileId, std::vector<uint8_t>> tiles;
  for (int x = 0; x < 4; ++x) tiles[{2, x, 1}] = std::vector<uint8_t>(30, static_cast<uint8_t>(x));
  const auto archive = buildPmtiles(tiles);
  const std::vector<uint8_t> header(archive.begin(), archive.begin() + 127);
  Outcomes tally;
  for (int i = 0; i < kMutations; ++i) {
    const ByteMutation m = mutateBytes(header, kSeed, static_cast<uint64_t>(i));
    expectValueOrError([&] { return datasets::decodePmtilesHeader(m.bytes, "h.pmtiles", archive.size()); },
                       "header " + std::to_string(i) + ": " + m.what, tally);
  }
  EXPECT_EQ(tally.threw, 0);
  EXPECT_GT(tally.refused, 0);
  EXPECT_GT(tally.ok, 0);
}

// Whole archives on disk through the source: open, list a zoom (walking leaves), read each tile.
TEST(PmtilesFuzz, ArchivesThroughTheSource) {
  std::map<geo::TileId, std::vector<uint8_t>> tiles;
  for (int x = 0; x < 8; ++x)
    for (int y = 0; y < 8; y += 3) tiles[{3, x, y}] = std::vector<uint8_t>(20 + x, static_cast<uint8_t>(x * y));
  const auto valid = buildPmtiles(tiles, {.gzipDirectories = true, .maxRootEntries = 4});
  const fs::path dir = ownTestDir();
  const fs::path file = dir / "a.pmtiles";
  Outcomes tally;
  StderrCapture printed(dir / "stderr.txt");
  for (int i = 0; i < kMutations / 3; ++i) {
    const ByteMutation m = i == 0 ? ByteMutation{valid, "none"} : mutateBytes(valid, kSeed, static_cast<uint64_t>(i));
    {
      std::ofstream f(file, std::ios::binary | std::ios::trunc);
      f.write(reinterpret_cast<const char*>(m.bytes.data()), static_cast<std::streamsize>(m.bytes.size()));
    }
    expectValueOrError(
        [&]() -> Status {
          auto s = datasets::openXyzSource(file.string());
          if (!s) return s.error();
          auto ids = (*s)->tilesAt(3, std::nullopt, 1000);
          if (!ids) return ids.error();
          for (const auto& id : *ids)
            if (auto t = (*s)->read(id); !t) return t.error();
          if (i == 0) {
            EXPECT_EQ(ids->size(), tiles.size());
          }
          return {};
        },
        "archive " + std::to_string(i) + ": " + m.what, tally);
  }
  const std::string noise = printed.text();
  EXPECT_TRUE(noise.empty()) << noise.substr(0, 2000);
  std::printf("archive: %d mutations, %d read, %d refused, %d threw\n", kMutations / 3, tally.ok, tally.refused,
              tally.threw);
  EXPECT_EQ(tally.threw, 0);
  EXPECT_GT(tally.refused, 0);
}

}  // namespace
}  // namespace vegstream::testing
