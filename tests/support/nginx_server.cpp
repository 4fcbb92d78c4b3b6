// NginxServer (nginx_server.h).

#include "tests/support/nginx_server.h"

#include <chrono>
#include <csignal>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace vegstream::testing {
namespace fs = std::filesystem;

namespace {

sockaddr_in loopback(int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<uint16_t>(port));
  return a;
}

std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string configText(const fs::path& root, const fs::path& work, int port) {
  const std::string w = work.string();
  std::ostringstream c;
  c << "daemon off;\n"
    << "master_process off;\n"
    << "worker_processes 1;\n"
    << "pid " << w << "/nginx.pid;\n"
    << "error_log " << w << "/error.log warn;\n"
    << "events { worker_connections 512; }\n"
    << "http {\n"
    << "  log_format vegstream '$uri $status $connection $connection_requests $body_bytes_sent';\n"
    << "  access_log " << w << "/access.log vegstream;\n"
    << "  client_body_temp_path " << w << "/tmp/body;\n"
    << "  proxy_temp_path " << w << "/tmp/proxy;\n"
    << "  fastcgi_temp_path " << w << "/tmp/fastcgi;\n"
    << "  uwsgi_temp_path " << w << "/tmp/uwsgi;\n"
    << "  scgi_temp_path " << w << "/tmp/scgi;\n"
    << "  types { image/png png; image/jpeg jpg; application/json json; }\n"
    << "  default_type application/octet-stream;\n"
    << "  sendfile on;\n"
    << "  keepalive_timeout 60s;\n"
    << "  keepalive_requests 100000;\n"
    << "  server {\n"
    << "    listen 127.0.0.1:" << port << ";\n"
    << "    server_name localhost;\n"
    << "    root " << root.string() << ";\n"
    << "    location / { }\n"
    << "  }\n"
    << "}\n";
  return c.str();
}

}  // namespace

int findFreeLoopbackPort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return -1;
  sockaddr_in a = loopback(0);
  int port = -1;
  socklen_t len = sizeof(a);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) == 0 &&
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) == 0)
    port = ntohs(a.sin_port);
  ::close(fd);
  return port;
}

bool loopbackPortAnswers(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return false;
  sockaddr_in a = loopback(port);
  const bool ok = ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) == 0;
  ::close(fd);
  return ok;
}

Result<std::unique_ptr<NginxServer>> NginxServer::start(const fs::path& root, const fs::path& workDir) {
  if (::access(kExecutable, X_OK) != 0)
    return makeError(ErrorKind::NotFound, std::string(kExecutable) + " is missing: run scripts/setup (nginx-light)");
  std::error_code ec;
  fs::create_directories(workDir / "tmp", ec);
  if (ec) return makeError(ErrorKind::Io, "cannot create " + workDir.string() + ": " + ec.message());
  const fs::path absRoot = fs::absolute(root);
  const fs::path absWork = fs::absolute(workDir);

  std::string lastProblem;
  // The free port may be taken by someone else before nginx binds it: try a few.
  for (int attempt = 0; attempt < 5; ++attempt) {
    const int port = findFreeLoopbackPort();
    if (port <= 0) return makeError(ErrorKind::Io, "cannot find a free loopback port");
    const fs::path conf = absWork / "nginx.conf";
    std::ofstream(conf) << configText(absRoot, absWork, port);

    const std::string prefix = absWork.string() + "/", confArg = conf.string(),
                      errArg = (absWork / "error.log").string(), outArg = (absWork / "stdout.log").string();
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, outArg.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    std::vector<std::string> args = {kExecutable, "-p", prefix, "-c", confArg, "-e", errArg};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, kExecutable, &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) return makeError(ErrorKind::Io, std::string("cannot start nginx: ") + std::strerror(rc));

    // nginx (an external process) says nothing when it listens: poll its port, with a deadline,
    // and notice it exiting. The only sleep of the tests outside tests/streaming, and why.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    bool exited = false;
    while (std::chrono::steady_clock::now() < deadline) {
      int status = 0;
      if (::waitpid(pid, &status, WNOHANG) == pid) {
        exited = true;
        break;
      }
      if (loopbackPortAnswers(port)) return std::unique_ptr<NginxServer>(new NginxServer(absWork, port, pid));
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (!exited) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
    lastProblem = readFile(absWork / "error.log") + readFile(absWork / "stdout.log");
  }
  return makeError(ErrorKind::Io, "nginx did not come up: " + lastProblem);
}

NginxServer::NginxServer(fs::path workDir, int port, pid_t pid)
    : workDir_(std::move(workDir)), port_(port), pid_(pid) {}

NginxServer::~NginxServer() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGTERM);
  ::waitpid(pid_, nullptr, 0);
}

std::string NginxServer::baseUrl() const { return "http://127.0.0.1:" + std::to_string(port_); }

std::vector<NginxLogLine> NginxServer::accessLog() const {
  std::vector<NginxLogLine> lines;
  std::ifstream in(workDir_ / "access.log");
  NginxLogLine l;
  while (in >> l.uri >> l.status >> l.connection >> l.connectionRequests >> l.bytesSent) lines.push_back(l);
  return lines;
}

}  // namespace vegstream::testing
