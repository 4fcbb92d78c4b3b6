#pragma once
// FaultHttpServer: a small HTTP/1.1 file server on 127.0.0.1 whose answers follow a schedule,
// so the HTTP source's retries, time-outs, cancellation and limits are tested against real
// sockets with known faults.
//
// One thread, poll()-driven, keep-alive: every connection is a small state machine (read the
// request → wait out its delay → write the answer → read the next), so delays on one connection
// never hold up another, and the server can measure how many requests are being answered at
// once (received, answer not yet finished or abandoned).
//
// Which fault a request gets: a fault scheduled for its request number (1-based, over all
// requests) wins; else the next one queued for its path (consumed in order); else the default
// fault (Serve unless setDefault says otherwise). Paths are given as the tile source sees them
// ("elevation/1/2/3.png"). A delay applies before the fault's own action.

#include <atomic>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <map>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace vegstream::testing {

enum class FaultAction {
  Serve,  // 200 with the file (404 when it does not exist)
  Status500,
  Status503,
  NotFound,  // 404 even when the file exists
  Truncate,  // announce the whole Content-Length, send half the body, close
  Reset,     // SO_LINGER 0 and close: the client sees a connection reset, no answer
};

struct Fault {
  FaultAction action = FaultAction::Serve;
  int delayMs = 0;
};

class FaultHttpServer {
 public:
  explicit FaultHttpServer(std::filesystem::path root);  // listens at once on a free port
  ~FaultHttpServer();                                    // closes everything, joins the thread
  FaultHttpServer(const FaultHttpServer&) = delete;
  FaultHttpServer& operator=(const FaultHttpServer&) = delete;

  int port() const { return port_; }
  std::string baseUrl() const;  // "http://127.0.0.1:PORT"

  void scheduleForPath(const std::string& path, std::vector<Fault> faults);
  void scheduleForRequest(uint64_t requestNumber, Fault fault);
  void setDefault(Fault fault);

  uint64_t requestsFor(const std::string& path) const;
  uint64_t totalRequests() const;
  uint64_t connectionsAccepted() const;
  int maxConcurrent() const;   // most requests being answered at one moment
  uint64_t abandoned() const;  // requests whose client closed before the answer was complete
  // Waits until done() — a condition on the counters above — holds, checking it again each time
  // the server changes them (no polling); false if it still does not hold after `limit`.
  bool waitUntil(const std::function<bool()>& done, std::chrono::milliseconds limit) const;

 private:
  struct Connection;
  void run();
  void onRequest(Connection& c, const std::string& path);
  Fault faultFor(const std::string& path);

  std::filesystem::path root_;
  int listenFd_ = -1;
  int wakeFds_[2] = {-1, -1};
  int port_ = 0;
  std::atomic<bool> stop_{false};

  mutable std::mutex mutex_;
  std::map<std::string, std::deque<Fault>> byPath_;
  std::map<uint64_t, Fault> byNumber_;
  Fault default_;
  std::map<std::string, uint64_t> counts_;
  uint64_t total_ = 0, accepted_ = 0, abandoned_ = 0;
  int active_ = 0, maxActive_ = 0;
  uint64_t generation_ = 0;                  // bumped (under mutex_) whenever a counter changes
  mutable std::condition_variable changed_;  // notified with it

  std::thread thread_;
};

}  // namespace vegstream::testing
