// libFuzzer's entry point for one target (fuzz/targets.h): compiled once per fuzz_<name> program
// with VEGSTREAM_FUZZ_ENTRY set to the target's function.

#include "fuzz/targets.h"

#ifndef VEGSTREAM_FUZZ_ENTRY
#error "VEGSTREAM_FUZZ_ENTRY names the target's function"
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return vegstream::fuzz::VEGSTREAM_FUZZ_ENTRY(data, size);
}
