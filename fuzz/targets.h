#pragma once
// The fuzz targets (fuzz/README.md): one plain function per reader, `int f(const uint8_t*,
// size_t)`, with libFuzzer's contract — any bytes, return 0, and a broken invariant or a crash is
// the finding. The same functions are linked two ways:
//   - clang, -fsanitize=fuzzer,address,undefined: one libFuzzer program per target
//     (fuzz/libfuzzer_entry.cpp defines LLVMFuzzerTestOneInput as a call of one of them);
//   - GCC, ordinary code: fuzz_regressions (fuzz/regression_runner.cpp), the ctest (label fuzz)
//     that runs every target over its fuzz/regressions/<target>/ and fuzz/corpus/<target>/ files.
// A reader's error value is a normal outcome; an exception escaping a reader is a finding (the
// readers promise values or errors), as is an error without a message.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <span>
#include <string>

namespace vegstream::fuzz {

using TargetFn = int (*)(const uint8_t* data, size_t size);

struct Target {
  const char* name;  // folder names under fuzz/corpus, fuzz/regressions; program fuzz_<name>
  TargetFn fn;
};

int datasetJson(const uint8_t* data, size_t size);
int flightPath(const uint8_t* data, size_t size);
int speciesCatalog(const uint8_t* data, size_t size);
int recordingJson(const uint8_t* data, size_t size);
int summaryJson(const uint8_t* data, size_t size);
int elevationTile(const uint8_t* data, size_t size);
int imageryTile(const uint8_t* data, size_t size);
int rasterSource(const uint8_t* data, size_t size);
int httpResponse(const uint8_t* data, size_t size);
int tileContract(const uint8_t* data, size_t size);

inline constexpr Target kTargets[] = {
    {"dataset_json", datasetJson},     {"flight_path", flightPath},     {"species_catalog", speciesCatalog},
    {"recording_json", recordingJson}, {"summary_json", summaryJson},   {"elevation_tile", elevationTile},
    {"imagery_tile", imageryTile},     {"raster_source", rasterSource}, {"http_response", httpResponse},
    {"tile_contract", tileContract},
};

// A broken invariant: printed, then abort() (libFuzzer records the input as a crash).
[[noreturn]] inline void fail(const char* what, const char* file, int line) {
  std::fprintf(stderr, "fuzz invariant broken at %s:%d: %s\n", file, line, what);
  std::fflush(stderr);
  std::abort();
}
#define VEGSTREAM_FUZZ_CHECK(cond) ((cond) ? (void)0 : ::vegstream::fuzz::fail(#cond, __FILE__, __LINE__))

// A Result's error must say something.
template <typename R>
void checkResult(const R& r) {
  if (!r.ok()) VEGSTREAM_FUZZ_CHECK(!r.error().message.empty());
}

inline std::string asText(const uint8_t* data, size_t size) {
  return size == 0 ? std::string() : std::string(reinterpret_cast<const char*>(data), size);
}
inline std::span<const uint8_t> asBytes(const uint8_t* data, size_t size) {
  return size == 0 ? std::span<const uint8_t>() : std::span<const uint8_t>(data, size);
}

// The pixel width an image's header states (PNG IHDR, or a JPEG SOF marker), 0 when none is
// found: the targets pass it as the expected tile size, so a seed of any size decodes in full.
int statedSide(std::span<const uint8_t> bytes);

}  // namespace vegstream::fuzz
