// peakResidentBytes (process_memory.h): Linux's /proc/self/status.

#include "core/process_memory.h"

#include <cstdio>
#include <fstream>
#include <string>

namespace vegstream {

uint64_t peakResidentBytes() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line)) {
    unsigned long long kb = 0;
    if (std::sscanf(line.c_str(), "VmHWM: %llu kB", &kb) == 1) return static_cast<uint64_t>(kb) * 1024u;
  }
  return 0;
}

}  // namespace vegstream
