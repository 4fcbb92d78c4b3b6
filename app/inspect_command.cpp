// `vegstream inspect` (inspect_command.h).

#include "app/inspect_command.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/exit_codes.h"
#include "vegetation/blade_shape.h"

namespace vegstream::app {

namespace {

constexpr const char* kTopics = "blade-shape";

Error userError(std::string message) { return makeError(ErrorKind::InvalidInput, std::move(message)); }

// The whole text must be one number (strtod accepts "nan"/"inf": the range checks reject them).
bool parseNumber(const std::string& text, double& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtod(text.c_str(), &end);
  return errno == 0 && end == text.c_str() + text.size();
}

int bladeShape(const InspectOptions& o, const Logger& log) {
  double k = 0.0, segments = 0.0, tilt = 0.0;
  if (o.stiffness.empty()) return reportError(log, userError("--stiffness: required by inspect blade-shape (k′ > 0)"));
  if (!parseNumber(o.stiffness, k) || !std::isfinite(k) || k <= 0.0)
    return reportError(log, userError("--stiffness " + o.stiffness + ": expected a number k′ > 0"));
  if (!parseNumber(o.segments, segments) || segments != std::floor(segments) || segments < 1 ||
      segments > vegetation::kMaxBladeSegments)
    return reportError(log, userError("--segments " + o.segments + ": expected a whole number 1 … " +
                                      std::to_string(vegetation::kMaxBladeSegments)));
  if (!parseNumber(o.rootTilt, tilt) || !std::isfinite(tilt) || tilt < 0.0 || tilt >= 0.5 * M_PI)
    return reportError(log, userError("--root-tilt " + o.rootTilt + ": expected radians in [0, π/2)"));
  const int n = static_cast<int>(segments);
  auto shape = vegetation::solveBladeShape(k, {n, tilt});
  if (!shape) return reportError(log, shape.error());
  nlohmann::json points = nlohmann::json::array();
  for (const auto& p : shape->points) points.push_back({p.x, p.y});
  const nlohmann::json out = {{"stiffness", k},
                              {"segments", n},
                              {"root_tilt", tilt},
                              {"phi", shape->phi},
                              {"inclination", shape->inclination},
                              {"points", points},
                              {"residual", shape->residual},
                              {"iterations", shape->iterations},
                              {"critical_stiffness", vegetation::criticalStiffness(n)}};
  std::cout << out.dump(2) << "\n";
  return kExitOk;
}

}  // namespace

CLI::App* addInspectCommand(CLI::App& cli, InspectOptions& o) {
  auto* cmd = cli.add_subcommand("inspect", std::string("Print a precomputed model as JSON; topics: ") + kTopics);
  cmd->add_option("topic", o.topic, std::string("What to inspect: ") + kTopics);
  cmd->add_option("--stiffness", o.stiffness, "blade-shape: spring stiffness k′ = k / (ρ h² g) > 0");
  cmd->add_option("--segments", o.segments, "blade-shape: rigid segments N, 1 … 16")->capture_default_str();
  cmd->add_option("--root-tilt", o.rootTilt, "blade-shape: the root's rest angle from vertical, rad, [0, π/2)")
      ->capture_default_str();
  return cmd;
}

int runInspect(const InspectOptions& o, const Logger& log) {
  if (o.topic.empty()) return reportError(log, userError(std::string("inspect: name a topic; topics: ") + kTopics));
  if (o.topic == "blade-shape") return bladeShape(o, log);
  return reportError(log, userError("inspect " + o.topic + ": unknown topic; topics: " + kTopics));
}

}  // namespace vegstream::app
