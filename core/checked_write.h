#pragma once
// Writing bytes to a file with every failure checked: each write(2) (short writes and EINTR
// retried), fsync and close. The error is one line naming the file and the operating system's
// reason ("disk full" for ENOSPC), never a silent truncation. Also: fsync of a file or a
// directory already written, so a rename that follows is durable.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "core/result.h"

namespace vegstream {

// The reason for errno `err` in words: "disk full" (ENOSPC), "disk quota exceeded" (EDQUOT),
// "file too large (File too large)" (EFBIG, e.g. RLIMIT_FSIZE), otherwise strerror(err).
std::string ioReason(int err);

// Io error "cannot write '<file>': <ioReason(err)>".
Error writeError(const std::filesystem::path& file, int err);

// Creates or truncates `file` and writes `bytes` to it, then fsyncs and closes it. Errors name
// `nameForErrors` (the user's target, not the temporary beside it).
Status writeAllBytes(const std::filesystem::path& file, std::span<const uint8_t> bytes,
                     const std::filesystem::path& nameForErrors);
Status writeAllText(const std::filesystem::path& file, std::string_view text,
                    const std::filesystem::path& nameForErrors);

// fsync(2) of an existing file or directory (opened read-only). Errors name `nameForErrors`.
Status syncPath(const std::filesystem::path& path, const std::filesystem::path& nameForErrors);

// Flushes every file and directory under `dir` to disk (syncfs of its file system).
Status syncDirectoryTree(const std::filesystem::path& dir, const std::filesystem::path& nameForErrors);

}  // namespace vegstream
