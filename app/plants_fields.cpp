// The printed digits of `vegstream plants` (plants_fields.h).

#include "app/plants_fields.h"

#include <cstdio>

namespace vegstream::app {

std::string formatNumber(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, v);
  return buf;
}

PlantFields fieldsOf(const scene::BoxPlant& r) {
  const auto f = formatNumber;
  return {f("%.10f", r.at.latDeg),      f("%.10f", r.at.lonDeg),        f("%.3f", r.at.heightM),
          f("%.4f", double(r.heightM)), f("%.5f", double(r.stiffness)), f("%.5f", double(r.sPrime))};
}

TreeFields fieldsOf(const scene::BoxTree& t) {
  const auto f = formatNumber;
  return {f("%.10f", t.at.latDeg),      f("%.10f", t.at.lonDeg),       f("%.3f", t.at.heightM),
          f("%.3f", double(t.heightM)), f("%.3f", double(t.crownM)), f("%.5f", double(t.sPrime))};
}

}  // namespace vegstream::app
