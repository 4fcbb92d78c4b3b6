#pragma once
// What the imagery's numbers mean, and how they become albedo: `import --radiometry
// auto|reflectance|srgb|stretch` (imagery_source.h applies the choice made here).
//
// - reflectance: ρ = DN · scale + offset per band (Landsat 8/9 Level-1 reflectance rescaling,
//   REFLECTANCE_MULT 2.0e-5 / REFLECTANCE_ADD −0.1, by default; Collection 2 Level-2 surface
//   reflectance is 2.75e-5 / −0.2), then dark-object subtraction per band (Chavez 1988, with the
//   darkest object assumed to reflect 1 % as in Chavez 1996's DOS1): the band's dark object is
//   the kDarkObjectPercent-th percentile of its valid pixels, and dark − 1 % is subtracted as
//   haze (nothing when the dark object is already below 1 %); the result is clamped to 0 … 1.
//   Level-1's division by the sine of the sun elevation is not applied: what the tiles hold is
//   the reflectance of the ground relative to flat ground under the acquisition sun, which
//   de-shading (deshading.h) keeps for flat ground.
// - srgb: 8-bit photographs are already sRGB-encoded: the bytes pass through.
// - stretch: each band's --stretch range (p1,p99 by default) onto 0 … 255, as display bytes;
//   not albedo.
// - auto: values within 0 … 255 → srgb. A Landsat product by its file names (a product id such
//   as LC08_L1TP_…, LC09_L2SP_…, a scene id such as LC80380342015230LGN00, or the word
//   "landsat") whose values are integer digital numbers whose 1st … 99th percentiles scale to
//   plausible reflectances (−0.05 … 1.2) → reflectance, with Level-2's scaling when the names
//   say L2SP / L2SR / _SR_B. Anything else beyond 8 bits → stretch, and the log says why.
//   --reflectance-scale / --reflectance-offset always win over the scaling the names suggest.

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"

namespace vegstream::datasets {

enum class RadiometryMethod { Auto, Reflectance, Srgb, Stretch };

const char* toString(RadiometryMethod m);  // "auto", "reflectance", "srgb", "stretch"
// Errors name the option: "--radiometry 'x': expected auto, reflectance, srgb or stretch".
Result<RadiometryMethod> parseRadiometryMethod(const std::string& text);

inline constexpr double kLandsatL1ReflectanceScale = 2.0e-5;
inline constexpr double kLandsatL1ReflectanceOffset = -0.1;
inline constexpr double kLandsatL2ReflectanceScale = 2.75e-5;
inline constexpr double kLandsatL2ReflectanceOffset = -0.2;
// Dark-object subtraction: the percentile (in percent) of a band's valid pixels taken as its
// darkest object, and the reflectance that object is assumed to have.
inline constexpr double kDarkObjectPercent = 0.01;
inline constexpr double kDarkObjectReflectance = 0.01;

struct RadiometryOptions {
  RadiometryMethod method = RadiometryMethod::Auto;
  std::optional<double> scale;   // --reflectance-scale: finite, > 0
  std::optional<double> offset;  // --reflectance-offset: finite
};

// What auto looks at: the merged raster's valid samples over all three channels.
struct ImageryValues {
  float lo = 0.0f, hi = 0.0f;  // extremes
  double p1 = 0.0, p99 = 0.0;  // 1st and 99th percentiles
  bool integers = true;        // every sample a whole number
};

enum class LandsatLevel { None, Level1, Level2 };
// From file names (and their parent directory's name): see the header comment.
LandsatLevel landsatFromNames(const std::vector<std::filesystem::path>& files);

struct RadiometryChoice {
  RadiometryMethod method = RadiometryMethod::Srgb;  // never Auto
  double scale = kLandsatL1ReflectanceScale;         // reflectance only
  double offset = kLandsatL1ReflectanceOffset;
  std::string why;  // one sentence for the log: what auto saw
};

// The method for `files` holding `values`. stretchGiven: --stretch was given (auto → stretch).
// Errors (InvalidInput, naming the option and the file): srgb asked for values beyond 0 … 255;
// --stretch with --radiometry reflectance or srgb.
Result<RadiometryChoice> chooseRadiometry(const RadiometryOptions& options, bool stretchGiven,
                                          const std::vector<std::filesystem::path>& files, const ImageryValues& values);

// The value at percentile p (0 … 100) of `values` (reordered; not empty).
double percentile(std::vector<float>& values, double p);

// In place on an interleaved 3-channel raster of `count` pixels (NaN = no data): digital numbers
// → reflectance (DN · scale + offset), minus each band's haze (dark object − 1 %), clamped to
// 0 … 1. Returns each band's dark-object reflectance (before the subtraction).
std::array<double, 3> toSurfaceReflectance(std::vector<float>& rgb, double scale, double offset);
// Its two halves, for imagery read window by window: each band's dark object over the valid
// pixels of `rgb` (the whole raster, or its overview), and the conversion of any window with
// those dark objects.
std::array<double, 3> darkObjects(const std::vector<float>& rgb, double scale, double offset);
void applySurfaceReflectance(std::vector<float>& rgb, double scale, double offset, const std::array<double, 3>& dark);

}  // namespace vegstream::datasets
