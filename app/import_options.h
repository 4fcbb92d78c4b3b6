#pragma once
// `vegstream import`'s options (ImportOptions, import_command.h) → the option structs of the
// GeoTIFF and the XYZ importers, each text option checked: a mistake is one InvalidInput error
// naming the option ("--bands '1,x': expected band numbers from 1, e.g. 1,2,3").

#include <atomic>

#include "app/import_command.h"
#include "core/result.h"
#include "datasets/geotiff_import.h"
#include "datasets/xyz_import.h"

namespace vegstream::app {

// A --dem import's options; `cancel` stops the import when set.
Result<datasets::GeoTiffImportOptions> geoTiffImportOptions(const ImportOptions& o, const std::atomic<bool>* cancel);

// An --xyz-elevation import's options; `cancel` stops the import when set.
Result<datasets::XyzImportOptions> xyzImportOptions(const ImportOptions& o, const std::atomic<bool>* cancel);

}  // namespace vegstream::app
