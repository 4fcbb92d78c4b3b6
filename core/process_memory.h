#pragma once
// What the operating system says about this process's memory.

#include <cstdint>

namespace vegstream {

// Peak resident set size of this process (VmHWM of /proc/self/status), 0 where unknown.
uint64_t peakResidentBytes();

}  // namespace vegstream
