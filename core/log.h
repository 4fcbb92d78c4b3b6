#pragma once
// Logging: a spdlog logger is injected into the components that report (never a global one
// fetched from inside a library). makeConsoleLogger builds the one the program passes down.

#include <memory>
#include <string>

#include <spdlog/logger.h>

namespace vegstream {

using Logger = std::shared_ptr<spdlog::logger>;

// Logs to stderr, so that stdout stays clean for JSON-printing subcommands.
Logger makeConsoleLogger(const std::string& name, spdlog::level::level_enum level);

// A logger that drops everything (tests and library callers that do not care).
Logger makeNullLogger();

}  // namespace vegstream
