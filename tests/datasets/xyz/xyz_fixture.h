#pragma once
// Shared by the XYZ source tests: the grandcanyon-xyz tiles of zoom 12 (2 × 2 terrain-RGB tiles
// and the paletted map over them) copied into the test's own "site" directory
// (site/elevation/{z}/{x}/{y}.png, site/imagery/…), the reference dataset imported from that
// directory, and the comparison of two datasets: every tile file byte for byte, and dataset.json
// field for field apart from the sources' paths (and, when asked, their descriptions).

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "datasets/dataset_format.h"
#include "datasets/xyz_import.h"
#include "tests/support/test_dirs.h"

namespace vegstream::testing {

inline std::filesystem::path grandCanyonXyz() {
  return std::filesystem::path(VEGSTREAM_DATASETS_DIR) / "grandcanyon-xyz";
}

inline std::vector<uint8_t> bytesOf(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void writeBytes(const std::filesystem::path& p, const std::vector<uint8_t>& bytes) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// The four zoom-12 tiles of the sample (758…759 × 1608…1609), all in both layers.
inline std::vector<geo::TileId> sampleTiles() {
  return {{12, 758, 1608}, {12, 758, 1609}, {12, 759, 1608}, {12, 759, 1609}};
}

// layer "terrain-rgb" or "map" of the sample → (tile → file bytes).
inline std::map<geo::TileId, std::vector<uint8_t>> sampleLayer(const std::string& layer) {
  std::map<geo::TileId, std::vector<uint8_t>> out;
  for (const auto& id : sampleTiles())
    out[id] = bytesOf(grandCanyonXyz() / layer / std::to_string(id.z) / std::to_string(id.x) /
                      (std::to_string(id.y) + ".png"));
  return out;
}

// Relative path → bytes of every file below `dir` except dataset.json.
inline std::map<std::string, std::vector<uint8_t>> tileFiles(const std::filesystem::path& dir) {
  std::map<std::string, std::vector<uint8_t>> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename() != "dataset.json")
      out[e.path().lexically_relative(dir).generic_string()] = bytesOf(e.path());
  return out;
}

inline nlohmann::json datasetJson(const std::filesystem::path& dir, bool dropSourceDescriptions) {
  auto j = nlohmann::json::parse(bytesOf(dir / "dataset.json"));
  for (auto& s : j["sources"]) {
    s.erase("path");
    if (dropSourceDescriptions) s.erase("description");
  }
  return j;
}

// Same tile files byte for byte, and the same dataset.json apart from the sources' paths.
inline void expectSameDataset(const std::filesystem::path& expected, const std::filesystem::path& actual,
                              bool dropSourceDescriptions = false) {
  const auto a = tileFiles(expected), b = tileFiles(actual);
  ASSERT_FALSE(a.empty());
  std::vector<std::string> namesA, namesB;
  for (const auto& [k, v] : a) namesA.push_back(k);
  for (const auto& [k, v] : b) namesB.push_back(k);
  ASSERT_EQ(namesA, namesB);
  for (const auto& [name, bytes] : a) EXPECT_TRUE(bytes == b.at(name)) << name << " differs";
  EXPECT_EQ(datasetJson(expected, dropSourceDescriptions).dump(1), datasetJson(actual, dropSourceDescriptions).dump(1));
}

class XyzSources : public ::testing::Test {
 protected:
  void SetUp() override {
    work_ = testOutputDir();
    site_ = work_ / "site";
    for (const auto& [layer, to] : {std::pair{"terrain-rgb", "elevation"}, std::pair{"map", "imagery"}})
      for (const auto& [id, bytes] : sampleLayer(layer))
        writeBytes(site_ / to / std::to_string(id.z) / std::to_string(id.x) / (std::to_string(id.y) + ".png"), bytes);
    auto r = import(siteTemplate("elevation"), siteTemplate("imagery"), work_ / "reference");
    ASSERT_TRUE(r.ok()) << r.error().message;
    reference_ = work_ / "reference";
    ASSERT_EQ(r->maxZoom, 12);
    ASSERT_EQ(r->elevationTiles, 5u);  // 4 at zoom 12, their parent at 11
    ASSERT_EQ(r->imageryTiles, 5u);
  }

  std::string siteTemplate(const std::string& layer) const { return (site_ / layer / "{z}/{x}/{y}.png").string(); }

  datasets::XyzImportOptions options(const std::string& elevation, const std::string& imagery,
                                     const std::filesystem::path& out) const {
    datasets::XyzImportOptions o;
    o.elevationTemplate = elevation;
    if (!imagery.empty()) o.imageryTemplate = imagery;
    o.encoding = datasets::ElevationEncoding::TerrainRgb;
    o.out = out;
    o.name = "grandcanyon";
    o.threads = 2;
    o.http.backoffBaseMs = 5;
    o.http.backoffMaxMs = 20;
    return o;
  }
  Result<datasets::DatasetMeta> import(const std::string& elevation, const std::string& imagery,
                                       const std::filesystem::path& out) const {
    return datasets::importXyzTiles(options(elevation, imagery, out), makeNullLogger());
  }

  std::filesystem::path work_, site_, reference_;
};

}  // namespace vegstream::testing
