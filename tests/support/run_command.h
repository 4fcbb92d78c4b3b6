#pragma once
// Runs the vegstream executable (or any command) the way a user would, for command-line tests:
// exit code, stdout and stderr captured separately.

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <cstdlib>
#include <sys/wait.h>
#include <unistd.h>

namespace vegstream::testing {

struct CommandResult {
  int exitCode = -1;
  std::string out;
  std::string err;
};

inline std::string readWhole(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// `args` is appended to the executable path as given (quote it yourself where needed).
inline CommandResult runCommand(const std::string& commandLine) {
  static int counter = 0;
  const std::filesystem::path dir = std::filesystem::path(VEGSTREAM_TEST_TMP) / "cmd";
  std::filesystem::create_directories(dir);
  const std::string tag = std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const auto outPath = dir / ("out_" + tag), errPath = dir / ("err_" + tag);
  const std::string full = commandLine + " >" + outPath.string() + " 2>" + errPath.string() + " </dev/null";
  const int status = std::system(full.c_str());
  CommandResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  r.out = readWhole(outPath);
  r.err = readWhole(errPath);
  std::filesystem::remove(outPath);
  std::filesystem::remove(errPath);
  return r;
}

inline CommandResult runVegstream(const std::string& args) {
  return runCommand(std::string("'") + VEGSTREAM_EXE + "' " + args);
}

// Number of lines in a text (a user mistake should produce exactly one).
inline int countLines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  if (!text.empty() && text.back() != '\n') ++n;
  return n;
}

}  // namespace vegstream::testing
