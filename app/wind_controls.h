#pragma once
// The window's wind keys (issue 19): each press steps the shared simulation's mean wind —
// speed, the direction it comes from, gustiness — and the result goes to
// FrameDriver::setWind. Plain numbers in and out (no GLFW), so the stepping and clamping are
// unit-tested without a window; window_input.* counts the presses, hud.* has sliders for the same
// values.

#include <string>

#include "simulation/simulation_options.h"

namespace vegstream::app {

inline constexpr double kWindSpeedStepMps = 1.0;         // ] / [
inline constexpr double kWindSpeedCoarseStepMps = 10.0;  // Shift + ] / [
inline constexpr double kWindDirectionStepDeg = 15.0;    // . / ,
inline constexpr double kGustinessStep = 0.1;            // ' / ;

// One frame's wind key presses: +1 per raising press, −1 per lowering one.
struct WindKeys {
  int speedSteps = 0;      // ] raises, [ lowers
  int directionSteps = 0;  // . turns clockwise (the wind comes from further east of north), , back
  int gustinessSteps = 0;  // ' raises, ; lowers
  bool coarse = false;     // Shift: speed steps of 10 m/s
  bool any() const { return speedSteps != 0 || directionSteps != 0 || gustinessSteps != 0; }
};

// `wind` after the presses: speed clamped to 0 … kMaxWindSpeedMps, gustiness to 0 … 1 (kept to
// hundredths, so repeated 0.1 steps do not drift), direction wrapped into [0, 360) — a command
// line's −90 becomes 270 on the first turn.
simulation::WindOptions stepWind(const simulation::WindOptions& wind, const WindKeys& keys);

// The same limits for a value from a HUD slider (which may overshoot by a rounding step).
simulation::WindOptions clampWind(const simulation::WindOptions& wind);

// "12.0 m/s from 270° (W), gusts 0.50": the HUD's wind line.
std::string describeWind(const simulation::WindOptions& wind);

// "N", "NE", … "NW" for a from-direction in degrees (any value).
const char* compassPoint(double directionDeg);

}  // namespace vegstream::app
