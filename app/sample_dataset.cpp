// The default datasets: the Zion sample, or the synthetic one where it is missing (sample_dataset.h).

#include "app/sample_dataset.h"

#include <cstdlib>
#include <string_view>

#include "datasets/geotiff_import.h"
#include "datasets/progress.h"
#include "datasets/synthetic_generator.h"

namespace vegstream::app {
namespace fs = std::filesystem;

namespace {
constexpr std::string_view kZionImageryDatetime = "2015-08-18T17:58:00Z";
}  // namespace

std::string samplesDirFromEnvironment(const std::string& compiledIn) {
  const char* env = std::getenv("VEGSTREAM_SAMPLES_DIR");
  return env && *env ? std::string(env) : compiledIn;
}

Result<fs::path> ensureZionSample(const fs::path& samplesDir, const fs::path& datasetDir, const Logger& log) {
  std::error_code ec;
  const fs::path zion = samplesDir / "zion";
  const bool withNir = fs::exists(zion / "landsat_b5.tif", ec);
  if (fs::exists(datasetDir / "dataset.json", ec)) {
    // An import made before the near-infrared layer (issue 18), the reflectance radiometry
    // (issue 39) or the colour calibration (issue 41) existed is this program's own cache:
    // imported again, so the species use NDVI and the calibrated colours and the tiles hold
    // albedo. Anything else there is left alone.
    auto meta = datasets::readDatasetMeta(datasetDir);
    if (!meta || meta->name != "zion") return datasetDir;
    const bool stale = (!meta->ndvi && withNir) || !meta->radiometry || meta->imageryDatetime.empty() ||
                       !meta->colourCalibration;
    if (!stale) return datasetDir;
    log->info("{} was imported by an older vegstream (no NDVI layer, reflectance or colour calibration): importing the Zion sample "
              "again",
              datasetDir.string());
    fs::remove_all(datasetDir, ec);
    if (ec) return makeError(ErrorKind::Io, datasetDir.string() + ": cannot remove the old import: " + ec.message());
  }
  if (!fs::exists(zion / "srtm.tif", ec))
    return makeError(
        ErrorKind::NotFound,
        (zion / "srtm.tif").string() + ": the Zion sample is missing; give a dataset directory (vegstream import)");
  log->info("importing the Zion sample once into {}", datasetDir.string());
  datasets::GeoTiffImportOptions o;
  o.dem = {(zion / "srtm.tif").string()};
  o.imagery.bands = {(zion / "landsat_b4.tif").string(), (zion / "landsat_b3.tif").string(),
                      (zion / "landsat_b2.tif").string()};
  // Landsat 8 digital numbers → surface reflectance (DN × 2e-5 − 0.1, dark-object subtracted),
  // de-shaded under the sun of the scene's acquisition: LC80380342015230LGN00, 2015-08-18 at
  // about 17:58 UTC.
  o.imagery.radiometry.method = datasets::RadiometryMethod::Reflectance;
  o.imageryDatetime = std::string(kZionImageryDatetime);
  if (withNir) o.nir = datasets::NirInput{zion / "landsat_b5.tif"};  // NDVI for the species
  o.heightResampling = datasets::HeightResampling::Cubic;
  o.out = datasetDir;
  o.name = "zion";
  o.attribution = "SRTM (CGIAR-CSI v4.1), Landsat 8 (USGS), via spDataLarge (CC0)";
  datasets::ProgressReporter progress("import zion", stderr, 0);
  auto meta = datasets::importGeoTiff(o, log, progress);
  if (!meta) return meta.error();
  return datasetDir;
}

Result<fs::path> ensureDefaultDataset(const fs::path& samplesDir, const fs::path& zionDir, const fs::path& syntheticDir,
                                      const Logger& log) {
  std::error_code ec;
  const fs::path srtm = samplesDir / "zion" / "srtm.tif";
  if (fs::exists(zionDir / "dataset.json", ec) || fs::exists(srtm, ec))
    return ensureZionSample(samplesDir, zionDir, log);
  if (fs::exists(syntheticDir / "dataset.json", ec)) {
    log->info("the Zion sample is missing ({}): flying over the synthetic dataset in {}", srtm.string(),
              syntheticDir.string());
    return syntheticDir;
  }
  log->info("the Zion sample is missing ({}): generating the synthetic dataset (vegstream generate) once into {}",
            srtm.string(), syntheticDir.string());
  fs::create_directories(syntheticDir.parent_path(), ec);
  datasets::SyntheticOptions o;  // the defaults of `vegstream generate`: 10 km around 46.55 N, 7.95 E
  o.out = syntheticDir;
  o.name = "synthetic";
  datasets::NullProgress progress;
  auto meta = datasets::generateSyntheticDataset(o, makeNullLogger(), progress);
  if (!meta) return meta.error();
  return syntheticDir;
}

}  // namespace vegstream::app
