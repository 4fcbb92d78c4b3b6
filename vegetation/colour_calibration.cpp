// The calibrated ground colour and its excess-green index (colour_calibration.h; ExG after
// Woebbecke et al. 1995). Float operations in the order of shaders/common/colour_calibration.glsl.
#include "vegetation/colour_calibration.h"

#include <algorithm>

#include "vegetation/colour_score.h"

namespace vegstream::vegetation {

bool ColourCalibration::isIdentity() const {
  const ColourCalibration id;
  return rows == id.rows;
}

glm::vec3 calibrateLinear(const ColourCalibration& c, glm::vec3 x) {
  glm::vec3 out;
  for (int i = 0; i < 3; ++i) {
    const glm::vec4& m = c.rows[static_cast<size_t>(i)];
    const float a = m.x * x.r;
    const float b = m.y * x.g;
    const float d = m.z * x.b;
    out[i] = std::clamp(((a + b) + d) + m.w, 0.0f, 1.0f);
  }
  return out;
}

float excessGreen(glm::vec3 c) {
  const float sum = (c.r + c.g) + c.b;
  if (!(sum >= kMinChromaticitySum)) return 0.0f;
  return ((2.0f * c.g - c.r) - c.b) / sum;
}

GroundColour calibratedGround(const ColourCalibration& c, glm::vec3 linear) {
  const glm::vec3 cal = calibrateLinear(c, linear);
  return {hsvFromLinear(cal), excessGreen(cal)};
}

}  // namespace vegstream::vegetation
