// `vegstream query` against what a file system can hold where a dataset's files should be (issue
// 42 items 1, 2, 5), run as a user would: a FIFO, a directory, a link to /dev/zero, a 5 MB
// dataset.json, a broken one, a valid PNG of the wrong size, a species catalog nested 100 000
// deep or smuggling terminal escapes. Each ends with exit 2, one line naming the file and the
// problem, no control character, in milliseconds (no hang, no "internal error", no crash).

#include <chrono>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include "datasets/tile_codec.h"
#include "geo/xyz_tiles.h"
#include "tests/datasets/query/query_fixture.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

bool hasControl(const std::string& s) {
  for (size_t i = 0; i + 1 < s.size(); ++i)  // the final newline ends the one line
    if (static_cast<unsigned char>(s[i]) < 0x20 || s[i] == 0x7f) return true;
  return false;
}

// One hostile change to a fresh copy of the dataset; what the one line must say.
struct Hostile {
  const char* name;
  std::function<void(const fs::path& copy, const datasets::DatasetMeta& meta)> make;
  const char* says;
};

const geo::TileId kTile{12, 759, 1608};  // the tile under the query point

fs::path elevation(const fs::path& d) { return datasets::elevationTilePath(d, kTile); }
fs::path imagery(const fs::path& d, const datasets::DatasetMeta& m) {
  return datasets::imageryTilePath(d, kTile, *m.imagery);
}
void replaceByFifo(const fs::path& f) {
  fs::remove(f);
  ASSERT_EQ(::mkfifo(f.c_str(), 0600), 0) << f;
}

std::vector<Hostile> hostileDatasets() {
  return {
      {"dataset_json_fifo", [](const fs::path& d, const auto&) { replaceByFifo(d / "dataset.json"); },
       "dataset.json: is a FIFO"},
      {"dataset_json_directory",
       [](const fs::path& d, const auto&) {
         fs::remove(d / "dataset.json");
         fs::create_directories(d / "dataset.json");
       },
       "dataset.json: is a directory"},
      {"dataset_json_5mb",
       [](const fs::path& d, const auto&) {
         std::ifstream in(d / "dataset.json");
         std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
         text.insert(1, std::string(5 << 20, ' '));
         std::ofstream(d / "dataset.json", std::ios::trunc) << text;
       },
       "a dataset.json is at most 4194304 bytes"},
      {"dataset_json_syntax",
       [](const fs::path& d, const auto&) {
         std::ofstream(d / "dataset.json", std::ios::trunc) << "{\n \"name\": x\n}";
       },
       "is not valid JSON: line 2, column 10: syntax error"},
      {"elevation_tile_fifo", [](const fs::path& d, const auto&) { replaceByFifo(elevation(d)); }, "is a FIFO"},
      {"elevation_tile_dev_zero",
       [](const fs::path& d, const auto&) {
         fs::remove(elevation(d));
         fs::create_symlink("/dev/zero", elevation(d));
       },
       "is a device"},
      {"elevation_tile_directory",
       [](const fs::path& d, const auto&) {
         fs::remove(elevation(d));
         fs::create_directories(elevation(d));
       },
       "is a directory"},
      {"imagery_tile_200px",
       [](const fs::path& d, const datasets::DatasetMeta& m) {
         datasets::ColorTile t;
         t.size = 200;
         t.rgba.assign(200 * 200 * 4, 120);
         fs::remove(imagery(d, m));
         ASSERT_TRUE(datasets::writeColorTile(imagery(d, m), t, *m.imagery).ok());
       },
       "is 200x200 pixels; dataset.json says tiles are 256 pixels a side"},
  };
}

class HostileQuery : public GrandCanyon, public ::testing::WithParamInterface<Hostile> {};

TEST_P(HostileQuery, OneLineExitTwoInMilliseconds) {
  const fs::path copy = testTmp(std::string("hostile_") + GetParam().name);
  fs::copy(dir(), copy, fs::copy_options::recursive);
  ASSERT_TRUE(meta().imagery.has_value());
  GetParam().make(copy, meta());
  const glm::dvec2 p = geo::tileXYToLonLat({759.3137, 1608.7071}, 12);
  const auto t0 = Clock::now();
  const auto r = runVegstream("query " + q(copy) + " --lat " + std::to_string(p.y) + " --lon " + std::to_string(p.x));
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 5.0);  // the process, start to end
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(countLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(GetParam().says), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  fs::remove_all(copy);
}

INSTANTIATE_TEST_SUITE_P(Cases, HostileQuery, ::testing::ValuesIn(hostileDatasets()),
                         [](const auto& p) { return std::string(p.param.name); });

// The embedded default catalog's text with the first species' "kind" replaced by `kindText`.
std::string catalogWithKind(const std::string& kindText) {
  std::ifstream in(fs::path(VEGSTREAM_SOURCE_DIR) / "config/species.json");
  nlohmann::json j = nlohmann::json::parse(in);
  j["species"][0]["kind"] = "KIND";
  std::string text = j.dump();
  text.replace(text.find("\"KIND\""), 6, kindText);
  return text;
}

TEST_F(GrandCanyon, SpeciesCatalogsThatAttackTheErrorTextGetOneEscapedBoundedLine) {
  const fs::path d = testTmp("hostile_species");
  fs::create_directories(d);
  const size_t depth = 100000;  // the error text's dump() recursed once per level: SIGSEGV
  std::ofstream(d / "deep.json") << catalogWithKind(std::string(depth, '[') + std::string(depth, ']'));
  std::ofstream(d / "escape.json") << catalogWithKind("\"\\u001b]0;owned\\u0007\\u001b[2J" + std::string(10000, 'k') +
                                                      "\"");
  ASSERT_EQ(::mkfifo((d / "fifo.json").c_str(), 0600), 0);
  const glm::dvec2 p = geo::tileXYToLonLat({759.3137, 1608.7071}, 12);
  const std::string at = " --lat " + std::to_string(p.y) + " --lon " + std::to_string(p.x);
  const std::pair<const char*, const char*> cases[] = {
      {"deep.json", "kind: must be \"grass\", \"gravel\", \"flowers\" or \"tree\" (got an array of 1 value(s))"},
      {"escape.json", "(got \"\\x1b]0;owned\\x07\\x1b[2Jkkk"},
      {"fifo.json", "fifo.json: is a FIFO"}};
  for (const auto& [file, says] : cases) {
    const auto r = runVegstream("query " + q(dir()) + at + " --species " + q(d / file));
    EXPECT_EQ(r.exitCode, 2) << file << ": " << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_FALSE(hasControl(r.err)) << r.err;
    EXPECT_LT(r.err.size(), 600u) << "bounded, whatever the value's length";
  }
  fs::remove_all(d);
}

}  // namespace
}  // namespace vegstream::testing
