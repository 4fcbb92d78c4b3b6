#pragma once
// Decoding the GeoTIFF GeoKey directory (tag 34735, with its double and ASCII parameter tags
// 34736 / 34737) into the few keys vegstream needs to name a CRS.

#include <optional>
#include <string>
#include <vector>

namespace vegstream::datasets {

// GeoKey ids (GeoTIFF 1.0 §6.2 / OGC GeoTIFF 1.1).
namespace geokey {
inline constexpr int kModelType = 1024;       // 1 projected, 2 geographic, 3 geocentric
inline constexpr int kRasterType = 1025;      // 1 PixelIsArea, 2 PixelIsPoint
inline constexpr int kCitation = 1026;        // GTCitationGeoKey
inline constexpr int kGeographicType = 2048;  // EPSG code of a geographic CRS
inline constexpr int kGeogCitation = 2049;
inline constexpr int kProjectedCsType = 3072;  // EPSG code of a projected CRS
inline constexpr int kPcsCitation = 3073;
inline constexpr int kUserDefined = 32767;  // "defined by other keys": no EPSG code
}  // namespace geokey

struct GeoKeys {
  std::optional<int> modelType;
  std::optional<int> rasterType;
  std::optional<int> geographicType;
  std::optional<int> projectedCsType;
  std::vector<std::string> citations;  // GT, PCS and geographic citations, in that order

  // The EPSG code the keys name: per GTModelType, the projected or the geographic type;
  // 0 when the keys name none (user-defined or absent).
  int epsg() const;
  // The citations joined with "; ", for messages.
  std::string description() const;
};

// Decodes the directory. nullopt when it is corrupt: a wrong version, fewer entries than its
// header claims, or a value that points outside its parameter tag — the same cases in which
// GDAL ignores the keys. `directory` holds the SHORT values of tag 34735.
std::optional<GeoKeys> decodeGeoKeys(const std::vector<double>& directory, const std::vector<double>& doubleParams,
                                     const std::string& asciiParams);

}  // namespace vegstream::datasets
