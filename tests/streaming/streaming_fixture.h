#pragma once
// Shared by the streaming tests: datasets made once and shared by the test processes (ctest runs
// each test in its own process, possibly in parallel), each process's own scratch directories
// under VEGSTREAM_TEST_TMP, and helpers to list a dataset's tiles and make wants.

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "datasets/dataset_format.h"
#include "datasets/geotiff_import.h"
#include "datasets/progress.h"
#include "datasets/synthetic_generator.h"
#include "streaming/tile_streamer.h"
#include "tests/support/test_dirs.h"

namespace vegstream::streaming::test {
namespace fs = std::filesystem;

inline fs::path testTmp(const std::string& name) {
  const auto p = fs::path(VEGSTREAM_TEST_TMP) / "streaming" / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p.parent_path());
  return p;
}

// A synthetic dataset of 3 km around the default centre, zooms 11 … 14 (about 20 tiles a layer
// at zoom 14, PNG imagery): seconds to make, real files for the local source.
inline Result<datasets::DatasetMeta> makeSynthetic(const fs::path& out) {
  datasets::SyntheticOptions o;
  o.out = out;
  o.name = "synthetic";
  o.sizeKm = 3.0;
  o.maxZoom = 14;
  o.minZoom = 11;
  o.threads = 2;
  datasets::NullProgress progress;
  return datasets::generateSyntheticDataset(o, makeNullLogger(), progress);
}

// The Zion sample (SRTM + Landsat bands 4/3/2, as de-shaded reflectance, JPEG imagery) at zoom ≤ 12.
inline Result<datasets::DatasetMeta> importZion(const fs::path& out, int maxZoom = 12) {
  const fs::path zion = fs::path(VEGSTREAM_DATASETS_DIR) / "zion";
  datasets::GeoTiffImportOptions o;
  o.dem = {(zion / "srtm.tif").string()};
  o.imagery.bands = {(zion / "landsat_b4.tif").string(), (zion / "landsat_b3.tif").string(),
                      (zion / "landsat_b2.tif").string()};
  o.imagery.radiometry.method = datasets::RadiometryMethod::Reflectance;  // as the demo imports it
  o.imageryDatetime = "2015-08-18T17:58:00Z";
  o.heightResampling = datasets::HeightResampling::Cubic;
  o.maxZoom = maxZoom;
  o.out = out;
  o.name = "zion";
  o.threads = 2;
  datasets::NullProgress progress;
  return datasets::importGeoTiff(o, makeNullLogger(), progress);
}

// The tiles of a layer at zoom z whose files exist.
inline std::vector<TileKey> tilesAt(const fs::path& dir, const datasets::DatasetMeta& meta, TileLayer layer, int z) {
  std::vector<TileKey> out;
  for (const auto& id : geo::tilesCovering(meta.bounds, z)) {
    const TileKey k{layer, id};
    if (fs::exists(dir / datasetRelativePath(k, meta))) out.push_back(k);
  }
  return out;
}

// Current wants, priority falling with the index (first = most important).
inline std::vector<TileWant> wantsOf(const std::vector<TileKey>& keys, bool lookAhead = false) {
  std::vector<TileWant> w;
  for (size_t i = 0; i < keys.size(); ++i) w.push_back({keys[i], double(keys.size() - i), lookAhead});
  return w;
}

// A dataset made once per build of this program for all its test processes (cachedFixture; tests
// only read it): Maker has kName and make(dir) → Result<DatasetMeta>. Made in SetUp, so that a
// test without its dataset fails (GoogleTest skips the tests of a failed SetUpTestSuite).
template <typename Maker>
class MadeDataset : public ::testing::Test {
 protected:
  void SetUp() override {
    auto dir = testing::cachedFixture(std::string("streaming-") + Maker::kName, testing::programKey(),
                                      [](const fs::path& out) -> Status {
                                        auto meta = Maker::make(out);
                                        if (!meta.ok()) return meta.error();
                                        return {};
                                      });
    ASSERT_TRUE(dir.ok()) << dir.error().message;
    auto meta = datasets::readDatasetMeta(*dir);
    ASSERT_TRUE(meta.ok()) << meta.error().message;
    dir_ = *dir;
    meta_ = *meta;
  }
  static const fs::path& dir() { return dir_; }
  static const datasets::DatasetMeta& meta() { return meta_; }

 private:
  static inline fs::path dir_;
  static inline datasets::DatasetMeta meta_;
};

struct SyntheticMaker {
  static constexpr const char* kName = "synthetic";
  static Result<datasets::DatasetMeta> make(const fs::path& dir) { return makeSynthetic(dir); }
};
struct ZionMaker {
  static constexpr const char* kName = "zion";
  static Result<datasets::DatasetMeta> make(const fs::path& dir) { return importZion(dir); }
};

// The synthetic dataset and the Zion sample (zoom ≤ 12), each made once per process.
using SyntheticDataset = MadeDataset<SyntheticMaker>;
using ZionDataset = MadeDataset<ZionMaker>;

}  // namespace vegstream::streaming::test
