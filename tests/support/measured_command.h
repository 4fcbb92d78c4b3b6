#pragma once
// Runs a command line as run_command.h does, and measures it: wall time, and the child's own
// peak resident memory (wait4's rusage of that child alone, ru_maxrss), for tests that bound a
// command's time and memory (issue 42: hostile servers end within their deadline at bounded
// memory).

#include <chrono>
#include <string>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/support/run_command.h"

namespace vegstream::testing {

struct MeasuredResult : CommandResult {
  double seconds = 0.0;
  double maxRssMb = 0.0;  // the shell's child is exec'd in place (exec below), so this is the command's
};

inline MeasuredResult runMeasured(const std::string& commandLine) {
  static int counter = 0;
  const std::filesystem::path dir = std::filesystem::path(VEGSTREAM_TEST_TMP) / "cmd";
  std::filesystem::create_directories(dir);
  const std::string tag = "m" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const auto outPath = dir / ("out_" + tag), errPath = dir / ("err_" + tag);
  const std::string full =
      "exec " + commandLine + " >'" + outPath.string() + "' 2>'" + errPath.string() + "' </dev/null";
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", full.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  rusage usage{};
  ::wait4(pid, &status, 0, &usage);
  MeasuredResult r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.maxRssMb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // kilobytes on Linux
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  r.out = readWhole(outPath);
  r.err = readWhole(errPath);
  std::filesystem::remove(outPath);
  std::filesystem::remove(errPath);
  return r;
}

}  // namespace vegstream::testing
