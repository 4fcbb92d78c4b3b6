#include "datasets/geokeys.h"

#include <cstddef>

namespace vegstream::datasets {
namespace {

constexpr int kDoubleParamsTag = 34736;
constexpr int kAsciiParamsTag = 34737;

std::optional<int> validCode(std::optional<int> code) {
  if (!code || *code <= 0 || *code == geokey::kUserDefined) return std::nullopt;
  return code;
}

}  // namespace

int GeoKeys::epsg() const {
  const auto projected = validCode(projectedCsType);
  const auto geographic = validCode(geographicType);
  if (modelType == 1) return projected.value_or(0);
  if (modelType == 2) return geographic.value_or(0);
  if (modelType) return 0;  // geocentric or unknown model: no 2-D CRS code to give
  // No model type: a projected code is the more specific of the two when both are present.
  return projected.value_or(geographic.value_or(0));
}

std::string GeoKeys::description() const {
  std::string out;
  for (const auto& c : citations) {
    if (c.empty()) continue;
    if (!out.empty()) out += "; ";
    out += c;
  }
  return out;
}

std::optional<GeoKeys> decodeGeoKeys(const std::vector<double>& directory, const std::vector<double>& doubleParams,
                                     const std::string& asciiParams) {
  // Header: KeyDirectoryVersion, KeyRevision, MinorRevision, NumberOfKeys; then 4 SHORTs a key.
  if (directory.size() < 4 || directory[0] != 1) return std::nullopt;
  const auto keys = static_cast<size_t>(directory[3]);
  if (directory.size() < 4 + 4 * keys) return std::nullopt;

  GeoKeys out;
  std::string gtCitation, geogCitation, pcsCitation;
  for (size_t k = 0; k < keys; ++k) {
    const double* entry = &directory[4 + 4 * k];
    const int id = static_cast<int>(entry[0]);
    const int location = static_cast<int>(entry[1]);
    const auto count = static_cast<size_t>(entry[2]);
    const auto offset = static_cast<size_t>(entry[3]);
    std::optional<int> shortValue;
    std::string text;
    if (location == 0) {
      shortValue = static_cast<int>(entry[3]);  // the value sits in the offset field
    } else if (location == kAsciiParamsTag) {
      if (offset > asciiParams.size() || count > asciiParams.size() - offset) return std::nullopt;
      text = asciiParams.substr(offset, count);
      // Each ASCII value ends with '|' in the shared parameter string.
      while (!text.empty() && (text.back() == '|' || text.back() == '\0' || text.back() == ' ')) text.pop_back();
    } else if (location == kDoubleParamsTag) {
      if (offset > doubleParams.size() || count > doubleParams.size() - offset) return std::nullopt;
      continue;  // ellipsoid parameters and the like: not needed to name an EPSG code
    } else if (location == 34735) {
      if (offset > directory.size() || count > directory.size() - offset) return std::nullopt;
      if (count == 1) shortValue = static_cast<int>(directory[offset]);
    } else {
      return std::nullopt;
    }
    switch (id) {
      case geokey::kModelType: out.modelType = shortValue; break;
      case geokey::kRasterType: out.rasterType = shortValue; break;
      case geokey::kGeographicType: out.geographicType = shortValue; break;
      case geokey::kProjectedCsType: out.projectedCsType = shortValue; break;
      case geokey::kCitation: gtCitation = text; break;
      case geokey::kGeogCitation: geogCitation = text; break;
      case geokey::kPcsCitation: pcsCitation = text; break;
      default: break;
    }
  }
  out.citations = {gtCitation, pcsCitation, geogCitation};
  return out;
}

}  // namespace vegstream::datasets
