#pragma once
// NDVI on the imagery's grid, for `vegstream import --imagery-nir FILE` (dataset_format.h's
// ndvi/ layer): a near-infrared GeoTIFF, possibly in another CRS and on another grid, and the
// imagery's red band before its stretch.
//
// NDVI = (NIR − red) / (NIR + red), the normalised difference vegetation index (Rouse, Haas,
// Schell & Deering 1974, "Monitoring vegetation systems in the Great Plains with ERTS"): −1 … 1,
// high over green vegetation, near 0 over rock and bare soil, negative over water and snow. It
// is computed here, at import, from the raw band values, because the stored imagery is
// stretched 8-bit colour: a ratio of stretched numbers is not a ratio of the sensor's. With
// Landsat digital numbers (no radiometric calibration applied) it is the same index GDAL gives
// from the band files (gdal_calc.py), not surface-reflectance NDVI.
//
// Every imagery pixel centre is taken to the NIR file's CRS through longitude/latitude
// (geo/projection.h; exactly every 8 pixels and bilinear in between, as SourceGrid does for
// tiles; the pixel itself when both files share one grid) and the NIR is sampled there
// bilinearly over its valid samples (sampleValue). The importer then resamples this raster onto
// the tiles exactly like the colour.

#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "core/log.h"
#include "core/result.h"
#include "datasets/geotiff_reader.h"
#include "datasets/source_grid.h"
#include "geo/crs.h"

namespace vegstream::datasets {

struct NirInput {
  std::filesystem::path file;      // --imagery-nir
  std::optional<int> assumeEpsg;   // --imagery-nir-crs (the imagery's --imagery-crs does not apply)
  uint64_t maxPixels = 400'000'000;
};

struct NdviRaster {
  // The imagery's grid (size and georeference), one channel: NDVI, NaN where there is none.
  Raster raster;
  geo::Crs nirCrs;
  std::string description;  // for dataset.json's sources
};

// NDVI of one pixel: NaN when either value is NaN or NIR + red ≤ 0 (no ratio to take),
// otherwise (NIR − red) / (NIR + red) clamped to −1 … 1 (a negative band value, possible in
// calibrated float data, would leave the range).
float ndviOf(float nir, float red);

// Reads `nir` and computes the NDVI at every pixel of `imagery`. rawRed: the imagery's red
// before the stretch, one value per imagery pixel, NaN = no data (PreparedImagery::rawRed).
// Errors name the NIR file: as readGeoTiff; more than one band; a CRS geo/ cannot read (state
// it with --imagery-nir-crs); no overlap with the imagery (both extents given); no pixel where
// both have data.
Result<NdviRaster> prepareNdvi(const NirInput& nir, const SourceGrid& imagery, std::span<const float> rawRed,
                               const Logger& log);

}  // namespace vegstream::datasets
