// Colour calibration estimate (colour_calibration.h): robust per-channel levels, chroma gain
// around Rec. 709 luminance, exposure; composed into one affine map. Double arithmetic over the
// pixels in their stored order and nth_element percentiles: the same input gives the same bytes.
#include "datasets/colour_calibration.h"

#include <algorithm>
#include <cmath>

namespace vegstream::datasets {
namespace {

constexpr std::array<double, 3> kLuma{0.2126, 0.7152, 0.0722};
constexpr double kMinRange = 1e-4;

// The value at percentile p (0 … 100) of v (reordered; not empty): nearest rank.
double percentileOf(std::vector<double>& v, double p) {
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(std::floor(p / 100.0 * static_cast<double>(v.size() - 1) + 0.5)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// The levels' gains, each kept within kMaxChannelGainRatio of their geometric mean.
std::array<double, 3> guardedGains(const ColourCalibrationRecord& c, const ColourReference& ref) {
  std::array<double, 3> g{};
  double logMean = 0.0;
  for (size_t i = 0; i < 3; ++i) {
    g[i] = (ref.white[i] - ref.black[i]) / std::max(c.white[i] - c.black[i], kMinRange);
    logMean += std::log(g[i]) / 3.0;
  }
  const double mean = std::exp(logMean);
  for (double& x : g)
    x = std::clamp(std::clamp(x, mean / kMaxChannelGainRatio, mean * kMaxChannelGainRatio), 1.0 / kMaxLevelsGain,
                   kMaxLevelsGain);
  return g;
}

// out = e (k I + (1 − k) 1 lumaᵀ) (g ⊙ x + d): M = that matrix · diag(g), o = that matrix · d.
void compose(ColourCalibrationRecord& c, const ColourReference& ref) {
  const double k = c.chromaGain, e = c.exposure;
  // Levels: y = g ⊙ x + d, d_c = B_c − g_c lo_c.
  std::array<double, 3> d{};
  for (size_t i = 0; i < 3; ++i) d[i] = ref.black[i] - c.gains[i] * c.black[i];  // B − g lo
  for (size_t r = 0; r < 3; ++r) {
    double off = 0.0;
    for (size_t col = 0; col < 3; ++col) {
      const double chroma = e * ((r == col ? k : 0.0) + (1.0 - k) * kLuma[col]);
      c.matrix[r * 3 + col] = chroma * c.gains[col];
      off += chroma * d[col];
    }
    c.offset[r] = off;
  }
}


// Luminance and chroma (max − min) / Y of every pixel through levels g ⊙ (x − lo) + B.
void measure(const std::array<std::vector<double>, 3>& ch, const std::array<double, 3>& gains,
             const std::array<double, 3>& lo, const std::array<double, 3>& black, std::vector<double>& lum,
             std::vector<double>& chroma) {
  const size_t n = ch[0].size();
  lum.resize(n);
  chroma.resize(n);
  for (size_t p = 0; p < n; ++p) {
    std::array<double, 3> y{};
    for (size_t i = 0; i < 3; ++i) y[i] = black[i] + gains[i] * (ch[i][p] - lo[i]);
    lum[p] = kLuma[0] * y[0] + kLuma[1] * y[1] + kLuma[2] * y[2];
    const double spread = std::max({y[0], y[1], y[2]}) - std::min({y[0], y[1], y[2]});
    chroma[p] = lum[p] > 1e-6 ? spread / lum[p] : -1.0;
  }
}

// The grey balance: per channel, the median of y_c / Y over the near-neutral pixels (chroma in
// the lowest kNeutralPercent of the non-dark ones), after the levels.
std::array<double, 3> greyBalance(const std::array<std::vector<double>, 3>& ch, const ColourCalibrationRecord& c,
                                  const std::array<double, 3>& black, const std::vector<double>& lum,
                                  const std::vector<double>& chroma, double dark) {
  std::vector<double> cs;
  for (size_t p = 0; p < lum.size(); ++p)
    if (lum[p] > dark && chroma[p] >= 0.0) cs.push_back(chroma[p]);
  if (cs.size() < 16) return {1.0, 1.0, 1.0};
  const double cut = percentileOf(cs, kNeutralPercent);
  std::array<double, 3> out{};
  for (size_t i = 0; i < 3; ++i) {
    std::vector<double> r;
    for (size_t p = 0; p < lum.size(); ++p)
      if (lum[p] > dark && chroma[p] >= 0.0 && chroma[p] <= cut)
        r.push_back((black[i] + c.gains[i] * (ch[i][p] - c.black[i])) / lum[p]);
    out[i] = r.empty() ? 1.0 : percentileOf(r, 50.0);
  }
  return out;
}

}  // namespace

ColourCalibrationRecord estimateColourCalibration(const std::vector<float>& linearRgb, const ColourReference& ref) {
  ColourCalibrationRecord c;
  std::array<std::vector<double>, 3> ch;
  for (size_t p = 0; p + 2 < linearRgb.size(); p += 3) {
    if (std::isnan(linearRgb[p]) || std::isnan(linearRgb[p + 1]) || std::isnan(linearRgb[p + 2])) continue;
    for (size_t i = 0; i < 3; ++i) ch[i].push_back(std::clamp(static_cast<double>(linearRgb[p + i]), 0.0, 1.0));
  }
  c.pixels = ch[0].size();
  if (c.pixels < 16) return c;  // too little to measure: identity
  for (size_t i = 0; i < 3; ++i) {
    std::vector<double> v = ch[i];
    c.black[i] = percentileOf(v, kBlackPercent);
    c.white[i] = percentileOf(v, kWhitePercent);
  }
  double spread = 0.0;
  for (size_t i = 0; i < 3; ++i) spread = std::max(spread, c.white[i] - c.black[i]);
  if (spread < kMinSpread) return c;  // one colour: no measure of the levels, the identity
  c.gains = guardedGains(c, ref);
  std::vector<double> lum, chroma;
  measure(ch, c.gains, c.black, ref.black, lum, chroma);
  std::vector<double> sortedLum = lum;
  double dark = std::max(percentileOf(sortedLum, kDarkPercent), 1e-6);
  // Grey balance onto the reference's: the near-neutral pixels' colour is the illuminant's.
  c.grey = greyBalance(ch, c, ref.black, lum, chroma, dark);
  for (size_t i = 0; i < 3; ++i) {
    const double w = std::clamp(ref.grey[i] / c.grey[i], 1.0 / kMaxGreyGain, kMaxGreyGain);
    c.gains[i] *= w;
  }
  measure(ch, c.gains, c.black, ref.black, lum, chroma);
  sortedLum = lum;
  dark = std::max(percentileOf(sortedLum, kDarkPercent), 1e-6);
  c.medianLuminance = percentileOf(sortedLum, 50.0);
  std::vector<double> bright;
  for (size_t p = 0; p < c.pixels; ++p)
    if (lum[p] > dark && chroma[p] >= 0.0) bright.push_back(chroma[p]);
  c.medianChroma = bright.empty() ? 0.0 : percentileOf(bright, 50.0);
  c.chromaGain = c.medianChroma > 1e-6 ? std::clamp(ref.chroma / c.medianChroma, kMinChroma, kMaxChroma) : 1.0;
  c.exposure =
      c.medianLuminance > 1e-6 ? std::clamp(ref.luminance / c.medianLuminance, kMinExposure, kMaxExposure) : 1.0;
  compose(c, ref);
  return c;
}

}  // namespace vegstream::datasets
