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
// Window by window: every imagery pixel centre of the window is taken to the NIR file's CRS
// through longitude/latitude (geo/projection.h; exactly every 8 pixels — anchored on the whole
// imagery's pixel grid, so windows agree where they overlap — and bilinear in between; the
// pixel itself when both files share one grid) and the NIR is sampled there bilinearly over its
// valid samples (sampleValue). The importer then resamples the window onto the tile exactly
// like the colour. The NIR may be a band of the imagery file itself (NAIP's 4th band).

#include <memory>
#include <optional>
#include <string>

#include "core/log.h"
#include "core/result.h"
#include "datasets/imagery_source.h"
#include "datasets/raster_source.h"
#include "datasets/source_grid.h"
#include "geo/crs.h"

namespace vegstream::datasets {

struct NirInput {
  std::string file;                  // --imagery-nir, or the --imagery file itself (--nir-band alone)
  int band = 1;                      // --nir-band (1-based)
  std::optional<geo::Crs> assumeCrs; // --imagery-nir-crs (the imagery's --imagery-crs does not apply)
};

// NDVI of one pixel: NaN when either value is NaN or NIR + red ≤ 0 (no ratio to take),
// otherwise (NIR − red) / (NIR + red) clamped to −1 … 1 (a negative band value, possible in
// calibrated float data, would leave the range).
float ndviOf(float nir, float red);

class NdviSource {
 public:
  // Opens `nir` (one band of it) and checks it overlaps the imagery. Errors name the NIR file:
  // as RasterSource::open's; a CRS PROJ cannot read (state it with --imagery-nir-crs); no
  // overlap with the imagery (both extents given).
  static Result<NdviSource> open(const NirInput& nir, const SourceGrid& imagery, const Logger& log);

  // The NDVI at every pixel of an imagery window (same size and geometry as w.colour, one
  // channel, NaN where there is none), from w.rawRed and the NIR sampled bilinearly at each
  // pixel's centre taken to the NIR's CRS. maxSide: the one the window was read with.
  Result<Raster> ndviFor(const ImageryWindow& w, int maxSide) const;

  const geo::Crs& nirCrs() const { return nir_->crs(); }
  const std::string& description() const { return description_; }
  const std::string& label() const { return nir_->label(); }

 private:
  std::vector<glm::dvec2> nirPositions(const Raster& window) const;

  std::shared_ptr<RasterSource> nir_;   // shared: grid_ points into it, and NdviSource moves
  std::shared_ptr<SourceGrid> grid_;
  const SourceGrid* imagery_ = nullptr;
  bool sameGrid_ = false;
  std::string description_;
};

}  // namespace vegstream::datasets
