// The "niche" object of a tree species (tree_niche.h, tree_niche_parse.h).
#include "vegetation/tree_niche_parse.h"

#include <cmath>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

namespace vegstream::vegetation {
namespace {

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// [lo, hi] with either end null (open); the bounds' sanity: [−500, 9000] m, [0, 90]°, [−500, 500] m.
bool parseRange(const nlohmann::json& v, const char* key, double least, double most, float (&out)[2],
                std::string& field, std::string& problem) {
  const std::string at = std::string(".") + key;
  if (!v.is_array() || v.size() != 2) {
    field = at;
    problem = "must be [low, high] (numbers, or null for an open end)";
    return false;
  }
  const float open[2] = {-std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
  for (int i = 0; i < 2; ++i) {
    const nlohmann::json& e = v[static_cast<size_t>(i)];
    field = at + "[" + std::to_string(i) + "]";
    if (e.is_null()) {
      out[i] = open[i];
      continue;
    }
    if (!e.is_number()) return (problem = "must be a number or null", false);
    const double d = e.get<double>();
    if (!(d >= least && d <= most))
      return (problem = "must be in " + fmt(least) + " … " + fmt(most) + " (got " + fmt(d) + ")", false);
    out[i] = static_cast<float>(d);
  }
  if (out[0] > out[1]) {
    field = at;
    problem = "low must be ≤ high (got " + fmt(out[0]) + " > " + fmt(out[1]) + ")";
    return false;
  }
  field.clear();
  return true;
}

}  // namespace

bool parseTreeNiche(const nlohmann::json& v, TreeNiche& out, std::string& field, std::string& problem) {
  if (!v.is_object()) {
    field.clear();
    problem = "must be an object (elevation_m, slope_deg, relief_m)";
    return false;
  }
  for (auto it = v.begin(); it != v.end(); ++it) {
    const std::string& k = it.key();
    bool ok = true;
    if (k == "elevation_m")
      ok = parseRange(*it, "elevation_m", -500.0, 9000.0, out.elevationM, field, problem);
    else if (k == "slope_deg")
      ok = parseRange(*it, "slope_deg", 0.0, 90.0, out.slopeDeg, field, problem);
    else if (k == "relief_m")
      ok = parseRange(*it, "relief_m", -500.0, 500.0, out.reliefM, field, problem);
    else {
      field = "." + k.substr(0, 80);
      problem = "unknown key (allowed here: elevation_m, slope_deg, relief_m)";
      return false;
    }
    if (!ok) return false;
  }
  return true;
}

}  // namespace vegstream::vegetation
