#pragma once
// NginxServer: Debian's nginx (/usr/sbin/nginx, from scripts/setup's nginx-light) serving a
// directory on 127.0.0.1 for the HTTP tests — the kind of static server DESIGN.md promises a
// dataset works with.
//
// Everything it writes stays in `workDir`: its own generated nginx.conf, pid file, error and
// access logs and temp paths. It runs in the foreground without a master process (one process,
// a child of the test), keep-alive on, and works for root and non-root users alike (without a
// master process nginx never switches user). The port is a free one found by binding port 0;
// start() returns once the port accepts connections. The destructor stops nginx (SIGTERM) and
// waits for it.
//
// The access log has one line per request: "<uri> <status> <connection> <connection_requests>
// <bytes_sent>", parsed by accessLog() — how tests see retries and connection reuse from the
// server's side.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <sys/types.h>

#include "core/result.h"

namespace vegstream::testing {

struct NginxLogLine {
  std::string uri;  // "/elevation/12/758/1608.png"
  int status = 0;
  uint64_t connection = 0;  // nginx's connection serial number
  uint64_t connectionRequests = 0;
  uint64_t bytesSent = 0;
};

class NginxServer {
 public:
  static constexpr const char* kExecutable = "/usr/sbin/nginx";

  // Errors name the problem and carry nginx's own error log when it did not come up.
  static Result<std::unique_ptr<NginxServer>> start(const std::filesystem::path& root,
                                                    const std::filesystem::path& workDir);
  ~NginxServer();
  NginxServer(const NginxServer&) = delete;
  NginxServer& operator=(const NginxServer&) = delete;

  int port() const { return port_; }
  std::string baseUrl() const;  // "http://127.0.0.1:PORT"
  std::vector<NginxLogLine> accessLog() const;

 private:
  NginxServer(std::filesystem::path workDir, int port, pid_t pid);
  std::filesystem::path workDir_;
  int port_ = 0;
  pid_t pid_ = -1;
};

// A TCP port on 127.0.0.1 that nobody listens on right now (bind port 0, read it, close).
int findFreeLoopbackPort();

// True once something accepts a connection on 127.0.0.1:port.
bool loopbackPortAnswers(int port);

}  // namespace vegstream::testing
