#pragma once
// Text from data (a JSON value, a file name, a tile's path or URL) made safe for a one-line
// message: control characters (and DEL) are escaped as \n, \t, \xHH, so nothing from a file
// reaches the terminal as a control sequence or breaks the one line; long text is cut to its
// first `maxChars` bytes (then "..."), so an error never echoes unbounded input.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace vegstream {

inline constexpr size_t kPrintableChars = 80;       // a value from data
inline constexpr size_t kPrintablePathChars = 400;  // a path: long ones are real

std::string printable(std::string_view text, size_t maxChars = kPrintableChars);
inline std::string printablePath(const std::filesystem::path& p) { return printable(p.string(), kPrintablePathChars); }

}  // namespace vegstream
