#pragma once
// Exit codes of the command line: 0 done, 2 a user mistake (one message naming the file or
// option and the problem), 1 anything else (driver or system failure, a bug).

#include <string>

#include "core/log.h"
#include "core/printable.h"
#include "core/result.h"

namespace vegstream::app {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitUserError = 2;
constexpr size_t kMaxMessageChars = 4000;  // far above any message vegstream writes

// The text with its line breaks turned into spaces and trailing spaces dropped: a message from a
// library (an exception's what(), a driver's string) stays the one line the contract promises.
// Any other control character left in it (from a file's data that no reader escaped) is
// escaped here, the last stop before the terminal (core/printable.h), and the line is bounded.
inline std::string oneLine(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return printable(text, kMaxMessageChars);
}

inline int reportError(const Logger& log, const Error& error) {
  log->error("{}", oneLine(error.message));
  return error.isUserError() ? kExitUserError : kExitFailure;
}

}  // namespace vegstream::app
