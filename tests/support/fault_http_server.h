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
//
// Delays run on the wall clock, or on a clock the test gives (a ManualClock): then a request is
// answered once that clock has passed its delay, and settleClock() after each move of it returns
// when the server has begun every answer that became due (no wall-clock pacing in the test).

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

#include "core/clock.h"

namespace vegstream::testing {

enum class FaultAction {
  Serve,  // 200 with the file (404 when it does not exist)
  Status500,
  Status503,
  NotFound,  // 404 even when the file exists
  Truncate,  // announce the whole Content-Length, send half the body, close
  Reset,     // SO_LINGER 0 and close: the client sees a connection reset, no answer
  // Hostile answers (issue 42):
  HtmlPage,     // 200, Content-Type text/html, an HTML error page (a proxy's "tile")
  HtmlAsImage,  // the same page, but Content-Type image/png: only decoding can tell
  EndlessBody,  // 200 without Content-Length, then zeros for ever (until the client closes)
  HugeLength,   // 200 announcing a Content-Length of 10 GB, then zeros for ever
  Slowloris,    // the file's answer, one byte every trickleMs (bytes trickling, never stalled)
  Stall,        // the request is read and never answered (until the client closes)
  Redirect,     // 302 to Fault::location
};

struct Fault {
  FaultAction action = FaultAction::Serve;
  int delayMs = 0;
  std::string location;  // Redirect: the Location header, as given
  int trickleMs = 200;   // Slowloris: the pause between two bytes
};

class FaultHttpServer {
 public:
  using Clock = std::chrono::steady_clock;
  // Listens at once on a free port. `delayClock` (outlives the server): what Fault::delayMs is
  // counted on; null: the wall clock.
  explicit FaultHttpServer(std::filesystem::path root, const vegstream::Clock* delayClock = nullptr);
  ~FaultHttpServer();  // closes everything, joins the thread
  FaultHttpServer(const FaultHttpServer&) = delete;
  FaultHttpServer& operator=(const FaultHttpServer&) = delete;

  int port() const { return port_; }
  std::string baseUrl() const;  // "http://127.0.0.1:PORT"

  void scheduleForPath(const std::string& path, std::vector<Fault> faults);
  void scheduleForRequest(uint64_t requestNumber, Fault fault);
  void setDefault(Fault fault);
  void clearFaults();  // every fault scheduled and the default: a healthy server again

  uint64_t requestsFor(const std::string& path) const;
  uint64_t totalRequests() const;
  uint64_t connectionsAccepted() const;
  int maxConcurrent() const;        // most requests being answered at one moment
  uint64_t abandoned() const;       // requests whose client closed before the answer was complete
  uint64_t bytesSent() const;       // every byte written to any connection (headers included)
  int activeRequests() const;       // requests received whose answer is not finished nor abandoned
  int answersBeingWritten() const;  // answers begun and not yet wholly sent (as of run()'s last pass)
  // After the test moved the delay clock: wakes the server and waits (up to `limit`) until it
  // has looked at every request against the clock's new time, so every answer due has begun.
  bool settleClock(std::chrono::milliseconds limit);
  // Waits until done() — a condition on the counters above — holds, checking it again each time
  // the server changes them (no polling); false if it still does not hold after `limit`.
  bool waitUntil(const std::function<bool()>& done, std::chrono::milliseconds limit) const;

 private:
  struct Connection;
  void run();
  void onRequest(Connection& c, const std::string& path);
  void answer(Connection& c);                            // the fault's answer, or a reset
  bool writeSome(Connection& c, Clock::time_point now);  // false once the connection is gone
  double delayNowS() const;                              // the delay clock's time
  void finish(Connection& c, bool byClient);
  Fault faultFor(const std::string& path);

  std::filesystem::path root_;
  vegstream::SteadyClock wallClock_;
  const vegstream::Clock* delayClock_;
  int listenFd_ = -1;
  int wakeFds_[2] = {-1, -1};
  int port_ = 0;
  std::atomic<bool> stop_{false};

  mutable std::mutex mutex_;
  std::map<std::string, std::deque<Fault>> byPath_;
  std::map<uint64_t, Fault> byNumber_;
  Fault default_;
  std::map<std::string, uint64_t> counts_;
  uint64_t total_ = 0, accepted_ = 0, abandoned_ = 0, bytesSent_ = 0;
  int active_ = 0, maxActive_ = 0;
  int writing_ = 0;
  uint64_t clockMoves_ = 0, clockMovesSeen_ = 0;  // settleClock(): asked, and looked at by run()
  uint64_t generation_ = 0;                       // bumped (under mutex_) whenever a counter changes
  mutable std::condition_variable changed_;       // notified with it

  std::thread thread_;
};

}  // namespace vegstream::testing
