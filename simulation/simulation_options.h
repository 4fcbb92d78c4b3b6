#pragma once
// What a user sets about the shared simulation (issue 19): the mean wind, its gustiness, the local
// wind sources a flight path declares, and the trail store's memory budget. Command-line options
// (app/simulation_cli.h) and a flight path's "wind" section (flight/flight_path.h) both end here;
// the command line wins where both give a value.

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace vegstream::simulation {

inline constexpr double kMaxWindSpeedMps = 100.0;
inline constexpr double kDefaultTrailBudgetMb = 16.0;

struct WindOptions {
  double speedMps = 0.0;      // mean wind at 10 m above the ground, 0 … 100
  double directionDeg = 0.0;  // where the wind comes FROM, clockwise from north (meteorological); any value
  double gustiness = 0.5;     // 0 … 1: turbulence and gust fronts relative to the mean speed
};

enum class WindSourceType { Fan = 1, Whirlwind = 2, Rotor = 3 };

// One local source at one instant, in the scene's local ENU frame (metres; x east, y north, z up).
struct WindSourceState {
  WindSourceType type = WindSourceType::Fan;
  glm::dvec3 position{0.0};  // the source's centre (a rotor's hub), z MSL
  double groundZ = 0.0;      // the ground under it, MSL
  double radiusM = 1.0;      // reach (fan: range; whirlwind, rotor: radius of the affected disc)
  double strengthMps = 0.0;  // peak wind speed it adds
  double directionDeg = 0.0; // fan only: the direction it blows TOWARDS, clockwise from north
};

// One collider at one instant (flight/flight_path.h Collider), local ENU, vertical axis.
struct ColliderState {
  glm::dvec3 centre{0.0};  // a capsule's middle, z MSL
  double radiusM = 1.0;
  double lengthM = 0.0;    // capsule: distance between the end-cap centres; 0 for a sphere
  double groundZ = 0.0;    // the ground under its centre, MSL
};

struct SimulationOptions {
  WindOptions wind;
  double trailBudgetMb = kDefaultTrailBudgetMb;  // > 0: the trail store's GPU memory
  bool enabled = true;                           // false: nothing moves (the pre-issue-19 frame)
};

}  // namespace vegstream::simulation
