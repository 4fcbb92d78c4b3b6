#pragma once
// Colour constancy at import (issue 41 item 1): one affine map in linear light, estimated from the
// imagery's own statistics, that takes any sensor's white balance, exposure, contrast stretch and
// saturation onto those of the reference scene the species catalog was written on. Only the
// species choice sees it (vegetation/colour_calibration.h applies it); the tiles keep the
// imagery's colours.
//
// Method (robust levels + chroma + exposure normalisation; cf. the "white patch"/"grey world"
// family of colour constancy, Ebner, "Color Constancy", Wiley 2007, ch. 6, here with percentiles
// instead of extremes, and a chroma gain around luminance as in Reinhard et al. 2001's
// statistics transfer, but per scene instead of per target image): over the valid pixels x of
// the overview (kStatisticsPixels at most), in linear light,
//   1. levels, per channel c: lo_c, hi_c = the kBlackPercent / kWhitePercent percentiles of x_c;
//      y_c = B_c + (W_c − B_c) · (x_c − lo_c) / (hi_c − lo_c), where B, W are the reference's
//      black and white points. Any per-channel gain and offset of the input (white balance,
//      exposure, stretch, haze) gives the same y: the levels are equivariant to them.
//      Guard: the channels' gains (W_c − B_c) / (hi_c − lo_c) are kept within kMaxChannelGainRatio
//      of their geometric mean, so a scene of one colour (a field filling the frame) is not
//      turned fully grey; a range below 1e-4 counts as 1e-4. A scene whose channels all span less
//      than kMinSpread (a flat synthetic image, one colour filling the frame) carries no measure
//      of its levels: the identity. Every gain stays within 1/kMaxLevelsGain … kMaxLevelsGain.
//   1b. grey balance: the near-neutral pixels (the kNeutralPercent least chromatic of the
//      non-dark ones, after the levels) are taken to be grey under the scene's light (a robust
//      grey-world on near-greys: roads, roofs, bare ground); per channel the median of y_c / Y over
//      them, n_c, is brought to the reference's, y_c ← y_c · n*_c / n_c (each factor clamped to
//      1/kMaxGreyGain … kMaxGreyGain). It takes out casts that the extremes do not show (a tint
//      in the mid-tones, a per-channel tone curve). Still equivariant: it is measured after the
//      levels.
//   2. chroma, around the luminance Y = 0.2126 R + 0.7152 G + 0.0722 B (Rec. 709):
//      z = Y + k (y − Y), k = C* / median over the non-dark pixels (Y above its kDarkPercent
//      percentile) of (max y − min y) / Y, clamped to [kMinChroma, kMaxChroma]. Y is unchanged,
//      and that chroma measure scales by exactly k, so a desaturated or oversaturated copy of a
//      scene gets back its saturation.
//   3. exposure: out = e z, e = Y* / median Y (all valid pixels), clamped to [kMinExposure,
//      kMaxExposure].
// All three are affine, so the map is out = M x + o (M 3×3, row-major, o 3): the numbers stored.
//
// The reference (B, W, C*, Y*) is the scene the default catalog's colours were read from: the
// Zion Landsat sample stretched p1–p99 (tests/support/zion_sample.h zionStretchedSample),
// measured by this estimator with the identity reference (kReference*, below). So Zion stays
// nearly as it was, and other imagery is shown to the catalog "as the Zion sample would look".
//
// Limits: the levels assume each scene spans a similar range of surfaces (some dark shadow,
// some bright ground) in every channel; a scene of one colour (all forest, all sand, snow) is
// pushed towards the reference's balance within the gain guard, and a scene that is nearly all
// vegetation or nearly all rock has its median saturation and luminance set to the reference's,
// which shifts it. Non-affine changes (gamma, tone curves) are undone only at the medians.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vegstream::datasets {

inline constexpr double kBlackPercent = 1.0, kWhitePercent = 99.0, kDarkPercent = 10.0;
inline constexpr double kMaxChannelGainRatio = 2.0;
inline constexpr double kMinSpread = 0.02, kMaxLevelsGain = 16.0;
inline constexpr double kNeutralPercent = 30.0, kMaxGreyGain = 1.5;
inline constexpr double kMinChroma = 0.4, kMaxChroma = 3.0;
inline constexpr double kMinExposure = 0.1, kMaxExposure = 10.0;

// The reference scene's statistics (linear light): the Zion sample stretched p1–p99, as this
// estimator measured it with B = 0, W = 1, C* = Y* = anything (`vegstream import` of the bands
// with --stretch p1,p99: its dataset.json's statistics: black 0 and white 1 in every channel, as
// the stretch makes them, median chroma 0.33258, median luminance 0.055635 of 1610784 pixels).
inline constexpr std::array<double, 3> kReferenceBlack{0.0, 0.0, 0.0};
inline constexpr std::array<double, 3> kReferenceWhite{1.0, 1.0, 1.0};
inline constexpr double kReferenceChroma = 0.33258;
inline constexpr double kReferenceLuminance = 0.055635;
inline constexpr std::array<double, 3> kReferenceGrey{1.0, 1.0, 1.0};

inline constexpr const char* kColourCalibrationMethod = "levels-chroma-exposure-1";

// dataset.json's "imagery.colour_calibration". Absent (old datasets, XYZ imports, the synthetic
// generator): identity.
struct ColourCalibrationRecord {
  std::string method = kColourCalibrationMethod;
  std::array<double, 9> matrix{1, 0, 0, 0, 1, 0, 0, 0, 1};  // M, row-major
  std::array<double, 3> offset{0, 0, 0};                    // o
  // The statistics it came from.
  uint64_t pixels = 0;                  // valid pixels measured
  std::array<double, 3> black{}, white{};  // lo_c, hi_c (linear)
  std::array<double, 3> gains{};        // levels' gains after the guard, times the grey balance's
  std::array<double, 3> grey{1, 1, 1};  // the near-neutral pixels' y_c / Y after the levels
  double medianChroma = 0.0;            // after levels, before k
  double medianLuminance = 0.0;         // after levels
  double chromaGain = 1.0, exposure = 1.0;  // k, e
};

// The reference values the estimate aims at (the constants above, or others for measuring).
struct ColourReference {
  std::array<double, 3> black = kReferenceBlack, white = kReferenceWhite;
  double chroma = kReferenceChroma, luminance = kReferenceLuminance;
  std::array<double, 3> grey = kReferenceGrey;
};

// Estimated from interleaved linear RGB (NaN = no data; values clamped to 0 … 1). nullopt-like:
// with fewer than 16 valid pixels, the identity (pixels tells how many there were).
ColourCalibrationRecord estimateColourCalibration(const std::vector<float>& linearRgb,
                                                  const ColourReference& reference = {});

}  // namespace vegstream::datasets
