#pragma once
// Exit codes of the command line: 0 done, 2 a user mistake (one message naming the file or
// option and the problem), 1 anything else (driver or system failure, a bug).

#include "core/log.h"
#include "core/result.h"

namespace vegstream::app {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitUserError = 2;

inline int reportError(const Logger& log, const Error& error) {
  log->error("{}", error.message);
  return error.isUserError() ? kExitUserError : kExitFailure;
}

}  // namespace vegstream::app
