// FaultHttpServer (fault_http_server.h).

#include "tests/support/fault_http_server.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <sstream>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

namespace vegstream::testing {
namespace fs = std::filesystem;
namespace {
using Clock = std::chrono::steady_clock;

constexpr size_t kEndlessChunk = 64 * 1024;  // zeros written per refill of an endless body
const char* const kHtmlPage =
    "<!DOCTYPE html><html><head><title>502 Bad Gateway</title></head><body><h1>Bad Gateway</h1>"
    "<p>The proxy server received an invalid response from an upstream server.</p></body></html>\n";

void setNonBlocking(int fd) { ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK); }

// An answer's head; announcedLength < 0: no Content-Length (the body ends when the connection does).
std::string head(int status, const char* reason, long long announcedLength,
                 const char* type = "application/octet-stream", const std::string& extra = {}) {
  std::ostringstream o;
  o << "HTTP/1.1 " << status << ' ' << reason << "\r\n";
  if (announcedLength >= 0) o << "Content-Length: " << announcedLength << "\r\n";
  o << "Content-Type: " << type << "\r\n"
    << extra << (announcedLength >= 0 ? "Connection: keep-alive\r\n\r\n" : "Connection: close\r\n\r\n");
  return o.str();
}

std::string response(int status, const char* reason, const std::string& body, size_t announcedLength) {
  return head(status, reason, static_cast<long long>(announcedLength)) + body;
}

}  // namespace

struct FaultHttpServer::Connection {
  enum class State { Reading, Waiting, Writing };
  int fd = -1;
  State state = State::Reading;
  std::string in;
  std::string path;  // of the request being answered
  Fault fault;
  double readyAtS = 0.0;  // on the delay clock; infinity: never
  std::string out;
  size_t sent = 0;
  bool closeAfterWrite = false;
  bool endless = false;          // refill `out` with zeros whenever it is sent
  int trickleMs = 0;             // > 0: one byte, then this pause
  Clock::time_point nextSendAt;  // trickling: not before this
  bool active = false;           // a request received and not yet answered
  bool closed = false;
};

FaultHttpServer::FaultHttpServer(fs::path root, const vegstream::Clock* delayClock)
    : root_(std::move(root)), delayClock_(delayClock ? delayClock : &wallClock_) {
  listenFd_ = ::socket(AF_INET, SOCK_STREAM, 0);
  assert(listenFd_ >= 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  socklen_t len = sizeof(a);
  [[maybe_unused]] const int bound = ::bind(listenFd_, reinterpret_cast<sockaddr*>(&a), sizeof(a));
  assert(bound == 0);
  ::listen(listenFd_, 128);
  ::getsockname(listenFd_, reinterpret_cast<sockaddr*>(&a), &len);
  port_ = ntohs(a.sin_port);
  setNonBlocking(listenFd_);
  [[maybe_unused]] const int piped = ::pipe(wakeFds_);
  assert(piped == 0);
  thread_ = std::thread([this] { run(); });
}

FaultHttpServer::~FaultHttpServer() {
  stop_ = true;
  const char byte = 1;
  [[maybe_unused]] const ssize_t n = ::write(wakeFds_[1], &byte, 1);
  thread_.join();
  ::close(listenFd_);
  ::close(wakeFds_[0]);
  ::close(wakeFds_[1]);
}

std::string FaultHttpServer::baseUrl() const { return "http://127.0.0.1:" + std::to_string(port_); }

void FaultHttpServer::scheduleForPath(const std::string& path, std::vector<Fault> faults) {
  std::lock_guard lock(mutex_);
  auto& q = byPath_[path];
  q.insert(q.end(), faults.begin(), faults.end());
}
void FaultHttpServer::scheduleForRequest(uint64_t requestNumber, Fault fault) {
  std::lock_guard lock(mutex_);
  byNumber_[requestNumber] = fault;
}
void FaultHttpServer::setDefault(Fault fault) {
  std::lock_guard lock(mutex_);
  default_ = fault;
}
void FaultHttpServer::clearFaults() {
  std::lock_guard lock(mutex_);
  byPath_.clear();
  byNumber_.clear();
  default_ = Fault{};
}
uint64_t FaultHttpServer::requestsFor(const std::string& path) const {
  std::lock_guard lock(mutex_);
  auto it = counts_.find(path);
  return it == counts_.end() ? 0 : it->second;
}
uint64_t FaultHttpServer::totalRequests() const {
  std::lock_guard lock(mutex_);
  return total_;
}
uint64_t FaultHttpServer::connectionsAccepted() const {
  std::lock_guard lock(mutex_);
  return accepted_;
}
int FaultHttpServer::maxConcurrent() const {
  std::lock_guard lock(mutex_);
  return maxActive_;
}
uint64_t FaultHttpServer::abandoned() const {
  std::lock_guard lock(mutex_);
  return abandoned_;
}
int FaultHttpServer::activeRequests() const {
  std::lock_guard lock(mutex_);
  return active_;
}
int FaultHttpServer::answersBeingWritten() const {
  std::lock_guard lock(mutex_);
  return writing_;
}
double FaultHttpServer::delayNowS() const { return delayClock_->nowS(); }
bool FaultHttpServer::settleClock(std::chrono::milliseconds limit) {
  uint64_t asked = 0;
  {
    std::lock_guard lock(mutex_);
    asked = ++clockMoves_;
  }
  const char byte = 1;
  [[maybe_unused]] const ssize_t n = ::write(wakeFds_[1], &byte, 1);
  std::unique_lock lock(mutex_);
  return changed_.wait_for(lock, limit, [&] { return clockMovesSeen_ >= asked; });
}
uint64_t FaultHttpServer::bytesSent() const {
  std::lock_guard lock(mutex_);
  return bytesSent_;
}

bool FaultHttpServer::waitUntil(const std::function<bool()>& done, std::chrono::milliseconds limit) const {
  const auto end = std::chrono::steady_clock::now() + limit;
  for (;;) {
    uint64_t seen = 0;
    {
      std::lock_guard lock(mutex_);
      seen = generation_;
    }
    if (done()) return true;  // done() takes mutex_ itself
    std::unique_lock lock(mutex_);
    if (!changed_.wait_until(lock, end, [&] { return generation_ != seen; })) {
      lock.unlock();
      return done();
    }
  }
}

Fault FaultHttpServer::faultFor(const std::string& path) {
  // Under mutex_.
  ++total_;
  ++counts_[path];
  if (auto it = byNumber_.find(total_); it != byNumber_.end()) return it->second;
  if (auto it = byPath_.find(path); it != byPath_.end() && !it->second.empty()) {
    const Fault f = it->second.front();
    it->second.pop_front();
    return f;
  }
  return default_;
}

void FaultHttpServer::onRequest(Connection& c, const std::string& path) {
  std::lock_guard lock(mutex_);
  c.path = path;
  c.fault = faultFor(path);
  c.active = true;
  maxActive_ = std::max(maxActive_, ++active_);
  ++generation_;
  changed_.notify_all();
  c.state = Connection::State::Waiting;
  c.readyAtS = delayNowS() + c.fault.delayMs / 1000.0;
}

// Ends a connection; a request still unanswered counts as abandoned unless we chose to drop it.
void FaultHttpServer::finish(Connection& c, bool byClient) {
  if (c.active) {
    std::lock_guard lock(mutex_);
    --active_;
    abandoned_ += byClient ? 1 : 0;
    c.active = false;
    ++generation_;
    changed_.notify_all();
  }
  ::close(c.fd);
  c.closed = true;
}

void FaultHttpServer::answer(Connection& c) {
  const Fault& f = c.fault;
  const FaultAction a = f.action;
  if (a == FaultAction::Reset) {
    linger l{1, 0};
    ::setsockopt(c.fd, SOL_SOCKET, SO_LINGER, &l, sizeof(l));
    finish(c, false);
    return;
  }
  if (a == FaultAction::Stall) {
    c.readyAtS = std::numeric_limits<double>::infinity();  // never: the client gives up and closes
    return;
  }
  std::string body;
  bool found = false;
  if (c.path.find("..") == std::string::npos) {
    std::ifstream file(root_ / c.path, std::ios::binary);
    if (file && fs::is_regular_file(root_ / c.path)) {
      body.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
      found = true;
    }
  }
  c.sent = 0;
  c.state = Connection::State::Writing;
  c.trickleMs = 0;
  c.endless = false;
  switch (a) {
    case FaultAction::Status500: c.out = response(500, "Internal Server Error", "error\n", 6); return;
    case FaultAction::Status503: c.out = response(503, "Service Unavailable", "busy\n", 5); return;
    case FaultAction::HtmlPage:
    case FaultAction::HtmlAsImage: {
      const std::string page = kHtmlPage;
      c.out =
          head(200, "OK", static_cast<long long>(page.size()), a == FaultAction::HtmlPage ? "text/html" : "image/png") +
          page;
      return;
    }
    case FaultAction::EndlessBody:
    case FaultAction::HugeLength:
      c.out = head(200, "OK", a == FaultAction::HugeLength ? 10'000'000'000LL : -1);
      c.endless = true;
      c.closeAfterWrite = true;
      return;
    case FaultAction::Redirect: c.out = head(302, "Found", 0, "text/html", "Location: " + f.location + "\r\n"); return;
    default: break;
  }
  if (a == FaultAction::NotFound || !found) {
    c.out = response(404, "Not Found", "missing\n", 8);
  } else if (a == FaultAction::Truncate) {
    c.out = response(200, "OK", body.substr(0, body.size() / 2), body.size());
    c.closeAfterWrite = true;
  } else {
    c.out = response(200, "OK", body, body.size());
    if (a == FaultAction::Slowloris) c.trickleMs = std::max(1, f.trickleMs);
  }
}

// Writes what it may of c.out; at its end, refills an endless body or finishes the answer.
bool FaultHttpServer::writeSome(Connection& c, Clock::time_point now) {
  if (c.trickleMs > 0 && now < c.nextSendAt) return true;
  const size_t want = c.trickleMs > 0 ? std::min<size_t>(1, c.out.size() - c.sent) : c.out.size() - c.sent;
  const ssize_t n = ::send(c.fd, c.out.data() + c.sent, want, MSG_NOSIGNAL);
  if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) {
    finish(c, true);
    return false;
  }
  if (n > 0) {
    c.sent += static_cast<size_t>(n);
    c.nextSendAt = now + std::chrono::milliseconds(c.trickleMs);
    std::lock_guard lock(mutex_);
    bytesSent_ += static_cast<uint64_t>(n);
  }
  if (c.sent < c.out.size()) return true;
  if (c.endless) {
    c.out.assign(kEndlessChunk, '\0');
    c.sent = 0;
    return true;
  }
  {
    std::lock_guard lock(mutex_);
    --active_;
    c.active = false;
    ++generation_;
    changed_.notify_all();
  }
  if (c.closeAfterWrite) {
    finish(c, false);
    return false;
  }
  c.state = Connection::State::Reading;
  c.out.clear();
  c.trickleMs = 0;
  return true;
}

void FaultHttpServer::run() {
  std::vector<std::unique_ptr<Connection>> conns;
  // Takes the next complete request out of c.in, if there is one.
  auto takeRequest = [&](Connection& c) {
    const size_t end = c.in.find("\r\n\r\n");
    if (end == std::string::npos) return;
    std::istringstream line(c.in.substr(0, c.in.find("\r\n")));
    std::string method, target;
    line >> method >> target;
    c.in.erase(0, end + 4);
    target = target.substr(0, target.find('?'));
    if (!target.empty() && target[0] == '/') target.erase(0, 1);
    onRequest(c, target);
  };
  while (!stop_) {
    std::vector<pollfd> fds{{listenFd_, POLLIN, 0}, {wakeFds_[0], POLLIN, 0}};
    auto now = Clock::now();
    const double delayNow = delayNowS();
    int timeoutMs = 100;
    for (auto& c : conns) {
      const bool writing = c->state == Connection::State::Writing && (c->trickleMs == 0 || now >= c->nextSendAt);
      fds.push_back({c->fd, writing ? short(POLLIN | POLLOUT) : short(POLLIN), 0});
      if (c->state == Connection::State::Waiting && std::isfinite(c->readyAtS))
        timeoutMs =
            std::min(timeoutMs, static_cast<int>(std::clamp(std::ceil((c->readyAtS - delayNow) * 1000.0), 0.0, 100.0)));
      if (c->state == Connection::State::Writing && c->trickleMs > 0) {
        const auto ms = std::chrono::ceil<std::chrono::milliseconds>(c->nextSendAt - now).count();
        timeoutMs = std::min(timeoutMs, static_cast<int>(std::max<long long>(0, ms)));
      }
    }
    ::poll(fds.data(), fds.size(), timeoutMs);
    if (stop_) break;
    uint64_t clockMove = 0;  // the settleClock() this pass answers: every request is looked at below
    if (fds[1].revents & POLLIN) {
      char drain[64];
      [[maybe_unused]] const ssize_t n = ::read(wakeFds_[0], drain, sizeof(drain));
    }
    {
      std::lock_guard lock(mutex_);
      clockMove = clockMoves_;
    }

    if (fds[0].revents & POLLIN) {
      for (int fd; (fd = ::accept(listenFd_, nullptr, nullptr)) >= 0;) {
        setNonBlocking(fd);
        auto c = std::make_unique<Connection>();
        c->fd = fd;
        conns.push_back(std::move(c));
        std::lock_guard lock(mutex_);
        ++accepted_;
        ++generation_;
        changed_.notify_all();
      }
    }
    now = Clock::now();
    for (size_t i = 0; i + 2 < fds.size(); ++i) {
      Connection& c = *conns[i];
      const short re = fds[i + 2].revents;
      if (re & (POLLIN | POLLHUP | POLLERR)) {
        char buf[4096];
        const ssize_t n = ::recv(c.fd, buf, sizeof(buf), 0);
        if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK)) {
          finish(c, true);
          continue;
        }
        if (n > 0) c.in.append(buf, static_cast<size_t>(n));
      }
      if (c.state == Connection::State::Reading) takeRequest(c);
      if (c.state == Connection::State::Waiting && delayNowS() >= c.readyAtS) answer(c);
      if (!c.closed && c.state == Connection::State::Writing && writeSome(c, Clock::now()) &&
          c.state == Connection::State::Reading)
        takeRequest(c);  // a request that came while we were busy
    }
    conns.erase(std::remove_if(conns.begin(), conns.end(), [](const auto& c) { return c->closed; }), conns.end());
    const int writing = static_cast<int>(std::count_if(
        conns.begin(), conns.end(), [](const auto& c) { return c->state == Connection::State::Writing; }));
    std::lock_guard lock(mutex_);
    if (clockMove > clockMovesSeen_ || writing != writing_) {
      clockMovesSeen_ = std::max(clockMovesSeen_, clockMove);
      writing_ = writing;
      ++generation_;
      changed_.notify_all();
    }
  }
  for (auto& c : conns) finish(*c, true);
}

}  // namespace vegstream::testing
