#pragma once
// The Zion sample with its NDVI layer (SRTM heights, Landsat bands 4-3-2 as de-shaded reflectance, band 5
// for the NDVI), imported in process by this test program's own importer once for all its test
// processes (cachedFixture keyed by the program): the ground the tree tests read.

#include <filesystem>
#include <string>

#include "core/log.h"
#include "datasets/geotiff_import.h"
#include "datasets/progress.h"
#include "tests/support/test_dirs.h"

namespace vegstream::testing {

inline Result<std::filesystem::path> zionWithNdvi() {
  return cachedFixture("zion-ndvi", programKey(), [](const std::filesystem::path& dir) -> Status {
    const std::filesystem::path zion = std::filesystem::path(VEGSTREAM_DATASETS_DIR) / "zion";
    datasets::GeoTiffImportOptions o;
    o.dem = {(zion / "srtm.tif").string()};
    o.imagery.bands = {(zion / "landsat_b4.tif").string(), (zion / "landsat_b3.tif").string(),
                      (zion / "landsat_b2.tif").string()};
    o.imagery.radiometry.method = datasets::RadiometryMethod::Reflectance;  // as the demo imports it
    o.imageryDatetime = "2015-08-18T17:58:00Z";
    datasets::NirInput nir;
    nir.file = (zion / "landsat_b5.tif").string();
    o.nir = nir;
    o.out = dir;
    o.name = "zion";
    o.threads = 2;
    datasets::NullProgress progress;
    auto meta = datasets::importGeoTiff(o, makeNullLogger(), progress);
    if (!meta) return meta.error();
    return {};
  });
}

}  // namespace vegstream::testing
