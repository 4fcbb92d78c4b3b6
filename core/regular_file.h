#pragma once
// The one checked opener for every file vegstream reads whole (dataset.json, tiles, flight
// paths, species catalogs, recordings): only a regular file is read, and only up to a
// documented ceiling checked before reading. The file is opened with O_NONBLOCK (a FIFO does not
// block the open) and checked with fstat on the same descriptor, so a directory, a FIFO, a
// socket or a device (a link to /dev/zero included) is refused in milliseconds with one line
// naming the file, never read until memory runs out, never hung on.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/result.h"

namespace vegstream {

// What is read, for the message ("a dataset.json", "a tile"), and the most bytes it may have.
struct FileCeiling {
  const char* what;
  uint64_t maxBytes;
};

// The documented ceilings (each far above any real file of its kind):
inline constexpr uint64_t kMiB = uint64_t{1} << 20;
// dataset.json: a few KiB in practice (georeference, zoom range, encodings).
inline constexpr FileCeiling kDatasetJsonCeiling{"a dataset.json", 4 * kMiB};
// One tile (PNG / JPEG / WebP): at most 4096 × 4096 pixels, so at most 64 MiB of RGBA plus the
// encoding's overhead; real tiles are under 1 MiB.
inline constexpr FileCeiling kTileFileCeiling{"a tile", 80 * kMiB};
// Small JSON documents people write or vegstream writes: flight paths, species catalogs,
// recording.json, summary.json.
inline constexpr FileCeiling kJsonFileCeiling{"a JSON file", 16 * kMiB};
// Tables a recording writes (frames.csv): one line per frame.
inline constexpr FileCeiling kTableFileCeiling{"a table", 1024 * kMiB};

// The file's bytes. Errors (one line naming the file):
//   NotFound      "<file>: <missingHint>" (no such file or directory on the way);
//   InvalidInput  not a regular file ("is a directory", "is a FIFO (named pipe)", "is a
//                 device", "is a socket"), larger than the ceiling, or permission denied;
//   Io            the operating system failed part-way through the read.
Result<std::vector<uint8_t>> readRegularFileBytes(const std::filesystem::path& file, const FileCeiling& ceiling,
                                                  const std::string& missingHint = "no such file");
// The first `maxBytes` bytes (fewer when the file is shorter) of a regular file of any size:
// enough to tell a format by its magic number. The same errors but for the ceiling.
Result<std::string> readRegularFileHead(const std::filesystem::path& file, size_t maxBytes,
                                        const std::string& missingHint = "no such file");
// The same as text.
Result<std::string> readRegularFile(const std::filesystem::path& file, const FileCeiling& ceiling,
                                    const std::string& missingHint = "no such file");

}  // namespace vegstream
