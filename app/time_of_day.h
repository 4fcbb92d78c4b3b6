#pragma once
// The window's time of day (issue 39): keys and a HUD slider move the date-time the flight's sun
// clock starts at (scene::Scene::setStartDatetime), so the sun moves at once and keeps moving
// with session time. Plain numbers in and out (no GLFW, no ImGui), unit-tested without a window;
// window_input.* counts the presses, hud.* has the slider, interactive_flight.cpp applies them.

#include <string>

#include "geo/datetime.h"
#include "geo/solar_position.h"

namespace vegstream::app {

inline constexpr double kTimeStepS = 30.0 * 60.0;         // - / =
inline constexpr double kTimeCoarseStepS = 3.0 * 3600.0;  // Shift + - / =

// One frame's time-of-day key presses: +1 per later press, −1 per earlier one.
struct TimeKeys {
  int steps = 0;        // = later, - earlier
  bool coarse = false;  // Shift: steps of 3 h
  bool any() const { return steps != 0; }
};

// `t` moved by the presses (across midnight into the next or previous day).
geo::DateTime stepTime(const geo::DateTime& t, const TimeKeys& keys);

// The time of day of `t` in its own offset, hours in [0, 24).
double localHours(const geo::DateTime& t);

// `t` on the same local date at `hours` (clamped to [0, 24 h − 1 min]), to the millisecond.
geo::DateTime atLocalHours(const geo::DateTime& t, double hours);

// "2024-06-21 10:00 -07:32, sun 109° (E), 60.4° up" — the HUD's sun line.
std::string describeSun(const geo::DateTime& t, const geo::SolarPosition& sun);

}  // namespace vegstream::app
