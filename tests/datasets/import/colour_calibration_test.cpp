// The import's colour calibration estimate (datasets/colour_calibration.h) on synthetic scenes:
// a per-channel gain and offset of the input (white balance, exposure, stretch, haze) leaves the
// calibrated colours as they were; a desaturated copy gets its chroma back; the reference scene
// itself maps to the identity; one-colour scenes stay within the guards; too few pixels give the
// identity; dataset.json round-trips it and names a bad field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

#include "datasets/colour_calibration.h"
#include "datasets/dataset_format.h"
#include "tests/support/test_dirs.h"

namespace vegstream::datasets {
namespace {

// A scene of linear colours: shadows, vegetation, rock and sand with noise.
std::vector<float> scene(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float base[4][3] = {{0.01f, 0.012f, 0.015f}, {0.04f, 0.07f, 0.03f}, {0.25f, 0.14f, 0.11f}, {0.5f, 0.45f, 0.35f}};
  std::vector<float> out;
  for (int i = 0; i < 20000; ++i) {
    const auto& b = base[i % 4];
    const float k = 0.6f + 0.8f * u(rng);
    for (int c = 0; c < 3; ++c) out.push_back(b[c] * k);
  }
  return out;
}

std::array<double, 3> apply(const ColourCalibrationRecord& c, const float* x) {
  std::array<double, 3> y{};
  for (size_t r = 0; r < 3; ++r) y[r] = c.matrix[r * 3] * x[0] + c.matrix[r * 3 + 1] * x[1] + c.matrix[r * 3 + 2] * x[2] + c.offset[r];
  return y;
}

double worstDifference(const std::vector<float>& a, const ColourCalibrationRecord& ca, const std::vector<float>& b,
                       const ColourCalibrationRecord& cb) {
  double worst = 0.0;
  for (size_t p = 0; p < a.size(); p += 3) {
    const auto x = apply(ca, &a[p]), y = apply(cb, &b[p]);
    for (size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(x[c] - y[c]));
  }
  return worst;
}

TEST(ColourCalibration, PerChannelGainAndOffsetOfTheInputChangeNothing) {
  const std::vector<float> a = scene(1);
  std::vector<float> b = a;
  const float gain[3] = {0.7f, 1.1f, 1.6f}, offset[3] = {0.02f, 0.0f, 0.05f};
  for (size_t p = 0; p < b.size(); ++p) b[p] = b[p] * gain[p % 3] + offset[p % 3];
  const auto ca = estimateColourCalibration(a), cb = estimateColourCalibration(b);
  EXPECT_EQ(ca.pixels, 20000u);
  const double worst = worstDifference(a, ca, b, cb);
  std::printf("gain/offset cast: worst calibrated difference %.2e (linear)\n", worst);
  EXPECT_LT(worst, 1e-4);
  // Without the calibration the two differ plainly.
  EXPECT_GT(std::abs(a[5] - b[5]), 0.01f);
}

TEST(ColourCalibration, ADesaturatedCopyGetsItsChromaBack) {
  const std::vector<float> a = scene(2);
  std::vector<float> b = a;
  for (size_t p = 0; p < b.size(); p += 3) {
    const float y = 0.2126f * b[p] + 0.7152f * b[p + 1] + 0.0722f * b[p + 2];
    for (size_t c = 0; c < 3; ++c) b[p + c] = y + 0.5f * (b[p + c] - y);
  }
  const auto ca = estimateColourCalibration(a), cb = estimateColourCalibration(b);
  EXPECT_NEAR(cb.medianChroma / ca.medianChroma, 0.5, 0.15);
  EXPECT_NEAR(cb.chromaGain / ca.chromaGain, 2.0, 0.5);
}

TEST(ColourCalibration, TheReferenceSceneIsTheIdentityAndOneColourStaysGuarded) {
  // A scene whose levels, chroma and luminance are the reference's.
  ColourReference ref;
  std::vector<float> a = scene(3);
  auto c = estimateColourCalibration(a, ref);
  // Its own levels as the reference's: the levels are the identity, and the medians measured
  // after them are the scene's own (how kReference* were measured on the Zion sample).
  const auto own = estimateColourCalibration(a, ColourReference{c.black, c.white, 1.0, 1.0});
  const auto balanced = estimateColourCalibration(a, ColourReference{c.black, c.white, 1.0, 1.0, own.grey});
  const ColourReference self{c.black, c.white, balanced.medianChroma, balanced.medianLuminance, own.grey};
  // Its own statistics as the reference: the identity.
  const auto id = estimateColourCalibration(a, self);
  for (size_t i = 0; i < 9; ++i) EXPECT_NEAR(id.matrix[i], i % 4 == 0 ? 1.0 : 0.0, 1e-9) << i;
  for (double o : id.offset) EXPECT_NEAR(o, 0.0, 1e-9);
  // A field of one green with a little texture (0.024 between its darkest and brightest red):
  // the levels' gains stay within kMaxChannelGainRatio of each other and within kMaxLevelsGain
  // (times the grey balance's kMaxGreyGain),
  // the chroma and exposure gains within their clamps.
  std::vector<float> green;
  for (int i = 0; i < 1000; ++i) green.insert(green.end(), {0.05f + 4e-3f * float(i % 7), 0.09f + 1e-5f * float(i % 5), 0.03f});
  const auto g = estimateColourCalibration(green);
  for (double x : g.gains) {  // the levels' gain times the grey balance's
    EXPECT_LE(x, kMaxLevelsGain * kMaxGreyGain);
    EXPECT_GE(x, 1.0 / (kMaxLevelsGain * kMaxGreyGain));
  }
  const double hi = std::max({g.gains[0], g.gains[1], g.gains[2]}), lo = std::min({g.gains[0], g.gains[1], g.gains[2]});
  EXPECT_LE(hi / lo, kMaxChannelGainRatio * kMaxChannelGainRatio + 1e-9);
  EXPECT_GE(g.chromaGain, kMinChroma);
  EXPECT_LE(g.chromaGain, kMaxChroma);
  EXPECT_GE(g.exposure, kMinExposure);
  EXPECT_LE(g.exposure, kMaxExposure);
  // One flat colour (every channel spans less than kMinSpread: a synthetic test scene): no
  // measure of the levels, the identity.
  std::vector<float> flat;
  for (int i = 0; i < 1000; ++i) flat.insert(flat.end(), {0.05f + 1e-5f * float(i % 7), 0.09f, 0.03f});
  EXPECT_EQ(estimateColourCalibration(flat).matrix, (std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1}));
  // Too few pixels (NaN is no data): the identity.
  const auto few = estimateColourCalibration({0.1f, 0.2f, 0.3f, NAN, NAN, NAN});
  EXPECT_EQ(few.pixels, 1u);
  EXPECT_EQ(few.matrix, (std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1}));
}

TEST(ColourCalibration, DatasetJsonKeepsItAndNamesABadField) {
  const std::filesystem::path dir = testing::testOutputDir();
  DatasetMeta m;
  m.name = "calib";
  m.bounds = {-1.0, -1.0, 1.0, 1.0};
  m.imagery = ImageryFormat::Jpeg;
  m.colourCalibration = estimateColourCalibration(scene(4));
  ASSERT_TRUE(writeDatasetMeta(dir, m).ok());
  auto back = readDatasetMeta(dir);
  ASSERT_TRUE(back.ok()) << back.error().message;
  ASSERT_TRUE(back->colourCalibration.has_value());
  EXPECT_EQ(back->colourCalibration->matrix, m.colourCalibration->matrix);
  EXPECT_EQ(back->colourCalibration->offset, m.colourCalibration->offset);
  EXPECT_EQ(back->colourCalibration->pixels, m.colourCalibration->pixels);
  // Without it: identity (nullopt), as datasets written before it.
  m.colourCalibration.reset();
  ASSERT_TRUE(writeDatasetMeta(dir, m).ok());
  back = readDatasetMeta(dir);
  ASSERT_TRUE(back.ok());
  EXPECT_FALSE(back->colourCalibration.has_value());
  // A bad matrix is named.
  std::ifstream in(dir / "dataset.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string bad = R"("colour_calibration": {"method": "levels-chroma-exposure-1", "matrix": [1, 0], "offset": [0, 0, 0], "statistics": {}}, "format")";
  const auto at = text.find("\"format\"", text.find("\"imagery\""));
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 8, bad);
  auto parsed = parseDatasetMeta(text, "x/dataset.json");
  ASSERT_FALSE(parsed.ok());
  EXPECT_NE(parsed.error().message.find("imagery.colour_calibration.matrix"), std::string::npos) << parsed.error().message;
}

}  // namespace
}  // namespace vegstream::datasets
