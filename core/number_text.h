#pragma once
// A number in a user-facing message as people write it: printf's %g (at most 6 significant
// digits, no trailing zeros), so "--tree-horizon-m 20000.5" reads back as 20000.5.

#include <cstdio>
#include <string>

namespace vegstream {

inline std::string numberText(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace vegstream
