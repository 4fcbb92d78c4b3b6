#pragma once
// Running the vegstream executable as a child process the tests control directly (no shell):
// with a file-size limit (RLIMIT_FSIZE, SIGXFSZ ignored, so a write past it fails with EFBIG as
// a full disk fails with ENOSPC), or in the background to be killed at a chosen moment.

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/run_command.h"

namespace vegstream::testing {

struct SpawnOptions {
  rlim_t maxFileBytes = RLIM_INFINITY;
  std::filesystem::path stdoutFile = "/dev/null", stderrFile = "/dev/null";
};

// Starts VEGSTREAM_EXE with `args`; returns its PID (-1 when fork failed).
inline pid_t spawnVegstream(const std::vector<std::string>& args, const SpawnOptions& o = {}) {
  std::vector<std::string> argv{VEGSTREAM_EXE};
  argv.insert(argv.end(), args.begin(), args.end());
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  ::signal(SIGXFSZ, SIG_IGN);  // inherited through exec: writes past the limit return EFBIG
  const rlimit limit{o.maxFileBytes, o.maxFileBytes};
  if (o.maxFileBytes != RLIM_INFINITY && ::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(126);
  const int in = ::open("/dev/null", O_RDONLY);
  const int out = ::open(o.stdoutFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int err = ::open(o.stderrFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (in < 0 || out < 0 || err < 0) ::_exit(126);
  ::dup2(in, 0);
  ::dup2(out, 1);
  ::dup2(err, 2);
  std::vector<char*> raw;
  for (std::string& a : argv) raw.push_back(a.data());
  raw.push_back(nullptr);
  ::execv(raw[0], raw.data());
  ::_exit(127);
}

// The exit code of `pid` once it ends (128 + signal when killed).
inline int waitExit(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

// Runs vegstream with `args` to the end under a file-size limit; stdout and stderr captured.
inline CommandResult runVegstreamLimited(const std::vector<std::string>& args, rlim_t maxFileBytes,
                                         const std::filesystem::path& scratchDir) {
  std::filesystem::create_directories(scratchDir);
  SpawnOptions o;
  o.stdoutFile = scratchDir / "limited.out";
  o.stderrFile = scratchDir / "limited.err";  // messages stay far below any limit used
  o.maxFileBytes = maxFileBytes;
  CommandResult r;
  r.exitCode = waitExit(spawnVegstream(args, o));
  r.out = readWhole(o.stdoutFile);
  r.err = readWhole(o.stderrFile);
  return r;
}

// Starts vegstream with `args` and sends SIGKILL after `delay` (if it still runs). Returns its
// exit code: 128 + 9 when the kill came first.
inline int runVegstreamKilledAfter(const std::vector<std::string>& args, std::chrono::microseconds delay) {
  const pid_t pid = spawnVegstream(args);
  const auto until = std::chrono::steady_clock::now() + delay;
  int status = 0;
  while (std::chrono::steady_clock::now() < until) {
    if (::waitpid(pid, &status, WNOHANG) == pid)
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ::kill(pid, SIGKILL);
  return waitExit(pid);
}

}  // namespace vegstream::testing
