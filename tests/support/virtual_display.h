#pragma once
// VirtualDisplay: a private X server (Xvfb, from scripts/setup's xvfb) for the window tests.
//
// Not `xvfb-run -a`: it takes the first display number without a lock file and only then starts
// Xvfb there, so two tests starting at once (ctest runs two at a time) can take the same number
// and one of them fails. `Xvfb -displayfd FD` picks a free display itself (the one whose socket
// it could bind) and writes its number to FD once it accepts clients: start() waits on that pipe
// — an event from the external process, bounded by a deadline — never on a sleep. The destructor
// stops the server (SIGTERM) and waits for it.

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/result.h"
#include "tests/support/run_command.h"

extern char** environ;

namespace vegstream::testing {

class VirtualDisplay {
 public:
  static constexpr const char* kExecutable = "/usr/bin/Xvfb";

  // `log` receives the server's output (named in the error when it does not come up).
  static Result<std::unique_ptr<VirtualDisplay>> start(const std::filesystem::path& log,
                                                       const std::string& screen = "640x480x24") {
    if (::access(kExecutable, X_OK) != 0)
      return makeError(ErrorKind::NotFound, std::string(kExecutable) + " is missing: run scripts/setup (xvfb)");
    int fds[2];
    if (::pipe(fds) != 0) return makeError(ErrorKind::Io, std::string("pipe: ") + std::strerror(errno));
    ::fcntl(fds[0], F_SETFD, FD_CLOEXEC);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addclose(&actions, fds[0]);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    std::vector<std::string> args = {kExecutable, "-displayfd", std::to_string(fds[1]), "-screen", "0", screen,
                                     "-nolisten", "tcp"};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    const int rc = ::posix_spawn(&pid, kExecutable, &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(fds[1]);
    if (rc != 0) {
      ::close(fds[0]);
      return makeError(ErrorKind::Io, std::string("cannot start Xvfb: ") + std::strerror(rc));
    }
    std::unique_ptr<VirtualDisplay> d(new VirtualDisplay(pid));
    // Xvfb writes "N\n" when it is ready, or closes the pipe by exiting.
    std::string number;
    pollfd p{fds[0], POLLIN, 0};
    while (number.find('\n') == std::string::npos && ::poll(&p, 1, 30'000) > 0) {
      char buf[16];
      const ssize_t n = ::read(fds[0], buf, sizeof(buf));
      if (n <= 0) break;
      number.append(buf, static_cast<size_t>(n));
    }
    ::close(fds[0]);
    if (number.find('\n') == std::string::npos)
      return makeError(ErrorKind::Io, "Xvfb did not come up within 30 s: " + readWhole(log));
    d->display_ = ":" + number.substr(0, number.find('\n'));
    return d;
  }

  ~VirtualDisplay() {
    ::kill(pid_, SIGTERM);
    ::waitpid(pid_, nullptr, 0);
  }
  VirtualDisplay(const VirtualDisplay&) = delete;
  VirtualDisplay& operator=(const VirtualDisplay&) = delete;

  const std::string& display() const { return display_; }  // ":N"
  // "DISPLAY=:N ", to put before a command in a shell command line.
  std::string environment() const { return "DISPLAY=" + display_ + " "; }

 private:
  explicit VirtualDisplay(pid_t pid) : pid_(pid) {}
  pid_t pid_;
  std::string display_;
};

}  // namespace vegstream::testing
