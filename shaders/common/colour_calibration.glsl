// The calibrated ground colour and its excess-green index: the GLSL twin of
// vegetation/colour_calibration.h/.cpp, operation for operation (the products kept apart with
// `precise` so no fused multiply-add changes a bit). Needs colour_score.glsl.
// `rows`: the affine map in linear light, xyz a row of M, w its offset (identity: no calibration).

const float kMinChromaticitySum = 1e-4;

vec3 calibrateLinear(vec4 rows[3], vec3 x) {
  precise vec3 outColour;
  for (int i = 0; i < 3; ++i) {
    precise float a = rows[i].x * x.r;
    precise float b = rows[i].y * x.g;
    precise float d = rows[i].z * x.b;
    precise float s = ((a + b) + d) + rows[i].w;
    outColour[i] = clamp(s, 0.0, 1.0);
  }
  return outColour;
}

float excessGreen(vec3 c) {
  precise float sum = (c.r + c.g) + c.b;
  if (!(sum >= kMinChromaticitySum)) return 0.0;
  precise float num = (2.0 * c.g - c.r) - c.b;
  return num / sum;
}

// xyz: HSV of the calibrated colour; w: its ExG.
vec4 calibratedGround(vec4 rows[3], vec3 linearColour) {
  vec3 c = calibrateLinear(rows, linearColour);
  return vec4(hsvFromLinear(c), excessGreen(c));
}
