// The default Zion dataset (app/sample_dataset.h) holds albedo: imported as Landsat surface
// reflectance, de-shaded under the scene's acquisition sun (2015-08-18T17:58:00Z), with that
// datetime recorded; and an import made by an older vegstream (no imagery.radiometry) is made
// again, while a current one is reused as it is.

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "app/sample_dataset.h"
#include "core/log.h"
#include "datasets/dataset_format.h"
#include "tests/support/test_dirs.h"

namespace vegstream::app {
namespace {
namespace fs = std::filesystem;

TEST(SampleDataset, ZionIsImportedAsReflectanceUnderItsAcquisitionSunAndStaleImportsAreRedone) {
  const fs::path dir = testing::testOutputDir() / "zion";
  auto made = ensureZionSample(VEGSTREAM_DATASETS_DIR, dir, makeNullLogger());
  ASSERT_TRUE(made) << made.error().message;
  auto meta = datasets::readDatasetMeta(dir);
  ASSERT_TRUE(meta) << meta.error().message;
  EXPECT_EQ(meta->imageryDatetime, "2015-08-18T17:58:00Z");
  ASSERT_TRUE(meta->radiometry);
  EXPECT_EQ(meta->radiometry->method, "reflectance");
  ASSERT_TRUE(meta->radiometry->deshading);
  EXPECT_EQ(meta->radiometry->deshading->source, "imagery datetime");
  EXPECT_TRUE(meta->ndvi);

  // Reused as it is: the same tiles (a marker file survives).
  std::ofstream(dir / "marker") << "kept";
  ASSERT_TRUE(ensureZionSample(VEGSTREAM_DATASETS_DIR, dir, makeNullLogger()));
  EXPECT_TRUE(fs::exists(dir / "marker"));

  // An older import (display-stretched, no radiometry record) is made again.
  datasets::DatasetMeta old = *meta;
  old.radiometry.reset();
  old.imageryDatetime.clear();
  ASSERT_TRUE(datasets::writeDatasetMeta(dir, old));
  ASSERT_TRUE(ensureZionSample(VEGSTREAM_DATASETS_DIR, dir, makeNullLogger()));
  EXPECT_FALSE(fs::exists(dir / "marker"));
  auto again = datasets::readDatasetMeta(dir);
  ASSERT_TRUE(again) << again.error().message;
  ASSERT_TRUE(again->radiometry);
  EXPECT_EQ(again->radiometry->method, "reflectance");
}

}  // namespace
}  // namespace vegstream::app
