#pragma once
// The sun a photograph was taken under, estimated from the photograph and the DEM when its
// time is unknown (import without --imagery-datetime): the sun direction whose shading
// (deshading.h) best explains the brightness, fitted by least squares of log-brightness:
//
//   log B_i = a_g(i) + log shading(n_i, s) + ε_i
//
// over samples i (a pixel's normal n_i and the log of its linear luminance B_i), with one free
// intercept a_g per group g (a block of 64 × 64 tile pixels): the mean log-albedo of the block,
// so that albedo varying from block to block (forest on the plateau, desert below) does not
// pass for shading. The sum of squared residuals is minimised over the sun's azimuth and
// elevation (5° … 85°) by a 5° grid search refined by a pattern search to 0.1°.
//
// The estimate is used only when the terrain can show it: at least kMinSlopedFraction of the
// samples steeper than 5°, and the shading explaining at least kMinExplainedVariance of the
// within-block variance of log-brightness. Otherwise `found` is false and `note` says why
// (de-shading is then skipped, and dataset.json says so).

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "datasets/deshading.h"

namespace vegstream::datasets {

inline constexpr double kMinSlopedFraction = 0.05;
inline constexpr double kMinExplainedVariance = 0.05;

struct ShadingSample {
  glm::vec3 normal{0.0f, 0.0f, 1.0f};  // unit, ENU
  float logBrightness = 0.0f;          // log of the linear luminance
  uint32_t group = 0;                  // dense 0 … groups − 1
};

struct SunEstimate {
  bool found = false;
  SunAngles sun;
  double explained = 0.0;  // 1 − SSE(sun) / SSE(no shading), within the groups
  std::string note;        // how well it fits, or why nothing was found
};

SunEstimate estimateSun(const std::vector<ShadingSample>& samples, double directFraction);

}  // namespace vegstream::datasets
