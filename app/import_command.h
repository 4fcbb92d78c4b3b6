#pragma once
// `vegstream import`: a DEM (+ imagery) from any raster GDAL reads, or existing XYZ tiles → a dataset directory
// (DESIGN.md "Dataset directory"). The options are registered here, so main.cpp only adds the
// subcommand and dispatches to runImport.

#include <cstdint>
#include <string>
#include <vector>

#include "core/log.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace vegstream::app {

struct ImportOptions {
  // Raster form (any raster GDAL reads, by path or URL; several --dem / --imagery mosaic).
  std::vector<std::string> dem, imagery;
  std::string imageryBands, stretch, demCrs, imageryCrs;
  std::string bands;                      // --bands 1,2,3 of --imagery
  std::string imageryNir, imageryNirCrs;  // near-infrared band → the NDVI layer
  int nirBand = 0;                        // --nir-band N (0: not given)
  std::string landcover, landcoverScheme = "auto", landcoverCrs;  // the landcover layer
  std::string canopyHeight, canopyHeightCrs;                      // the canopy layer (a CHM)
  double demNodata = 0.0;
  std::string heightResampling = "bilinear";
  // Imagery radiometry and de-shading (datasets/radiometry.h, deshading_plan.h).
  std::string radiometry = "auto";
  std::string reflectanceScale, reflectanceOffset;  // empty: the defaults of the radiometry
  std::string imageryDatetime;                      // ISO 8601 with a zone
  std::string imagerySun;                           // "AZ,EL" degrees
  std::string deshading = "on";
  // XYZ form (templates by path or URL, MBTiles, PMTiles; datasets/xyz_source.h).
  std::string xyzElevation, xyzImagery;
  bool allowRedirects = false;  // URL sources: follow HTTP redirects to other hosts too
  std::string bounds;  // "W,S,E,N" degrees: the area of an XYZ import (required for URL templates)
  // Both.
  std::string out, name, attribution;
  std::string encoding = "terrarium";  // output encoding (GeoTIFF) / source encoding (XYZ)
  std::string imageryFormat;           // jpeg (GeoTIFF default) or png (XYZ default)
  int maxZoom = -1, minZoom = -1;      // -1: chosen from the data
  int jpegQuality = 90;
  size_t memoryMb = 512;
  bool resume = false;
  int threads = 0;

  // Which options the user gave (set by addImportCommand).
  CLI::Option* demNodataOpt = nullptr;
  CLI::Option* encodingOpt = nullptr;
};

// Registers `import` and its options on `cli`; the options fill `options`.
CLI::App* addImportCommand(CLI::App& cli, ImportOptions& options);

// Exit code: 0 done, 2 a user mistake (one message naming the file and the problem, nothing
// left at --out), 1 a system failure, 130 interrupted (nothing left at --out).
int runImport(const ImportOptions& options, const Logger& log);

}  // namespace vegstream::app
