#pragma once
// The Zion sample (SRTM heights + Landsat bands 4-3-2 as de-shaded surface reflectance, and band 5 for the NDVI
// layer, as the README imports it) imported by this build's vegstream, once for all the test processes of a folder (cachedFixture), on
// first use — never at static-initialisation time, which also runs when the build lists the
// tests. Tests must not change it.

#include <filesystem>
#include <string>

#include "core/result.h"
#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"

namespace vegstream::testing {

// The Zion bands imported once under `name` with the imagery options `imageryArgs`, by the first
// test program of the folder that asks (executableKey: the import is vegstream's alone).
inline Result<std::filesystem::path> zionImport(const std::string& name, const std::string& imageryArgs) {
  const std::string z = std::string(VEGSTREAM_DATASETS_DIR) + "/zion/";
  const std::string args = "import --dem " + z + "srtm.tif --imagery-bands " + z + "landsat_b4.tif," + z +
                           "landsat_b3.tif," + z + "landsat_b2.tif --imagery-nir " + z + "landsat_b5.tif " + imageryArgs;
  return cachedFixture(name, executableKey(args), [&](const std::filesystem::path& dir) -> Status {
    const auto r = runVegstream(args + " --out '" + dir.string() + "'");
    if (r.exitCode != 0)
      return makeError(ErrorKind::Internal, "vegstream import: exit " + std::to_string(r.exitCode) + ": " + r.err);
    return {};
  });
}

inline Result<std::filesystem::path> zionSampleDataset() {
  return zionImport("zion-sample", "--radiometry reflectance --imagery-datetime 2015-08-18T17:58:00Z");
}

// The same bands display-stretched p1–p99 as the importer did before issue 39 (the colours the
// default species catalog's references were read from; its tests of the catalog itself use it).
inline Result<std::filesystem::path> zionStretchedSample() { return zionImport("zion-sample-stretched", "--stretch p1,p99"); }

}  // namespace vegstream::testing
