#pragma once
// ScriptedSource: a TileSource test double for the streamer's state machine. A script decides
// each request's answer when it starts (or holds it until the test calls reply()); answers are
// delivered by the source's own thread, as a real source does. cancel() answers a held request
// Cancelled, unless `ignoreCancel` is set: then the request stays held, so the test can deliver
// an Ok after the cancel (a callback racing the cancellation).

#include <condition_variable>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "streaming/tile_source.h"

namespace vegstream::streaming::test {

class ScriptedSource final : public TileSource {
 public:
  // nullopt: hold the request until reply(). `attempt` counts starts of the same path (1, 2, …).
  using Script = std::function<std::optional<FetchResult>(const std::string& path, int attempt)>;

  explicit ScriptedSource(Script script = {}) : script_(std::move(script)), thread_([this] { run(); }) {}
  ~ScriptedSource() override {
    {
      std::lock_guard lock(mu_);
      for (auto& [id, h] : held_) queue_.push_back({std::move(h.done), cancelled(id)});
      held_.clear();
      stopping_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }

  bool ignoreCancel = false;

  std::string describe() const override { return "scripted"; }
  Result<std::string> readText(const std::string& path) override {
    return makeError(ErrorKind::NotFound, path + ": the scripted source has no files");
  }
  void start(RequestId id, const std::string& path, FetchCallback done) override {
    std::optional<FetchResult> r;
    {
      std::lock_guard lock(mu_);
      started_.push_back({id, path});
      ++counters_.requestsStarted;
      ++inFlight_;
      const int attempt = ++attempts_[path];
      if (script_) r = script_(path, attempt);
      if (!r) {
        held_[id] = Held{path, std::move(done)};
        return;
      }
      r->id = id;
      queue_.push_back({std::move(done), std::move(*r)});
    }
    cv_.notify_all();
  }
  void cancel(RequestId id) override {
    {
      std::lock_guard lock(mu_);
      cancels_.push_back(id);
      auto it = held_.find(id);
      if (ignoreCancel || it == held_.end()) return;
      queue_.push_back({std::move(it->second.done), cancelled(id)});
      held_.erase(it);
    }
    cv_.notify_all();
  }
  std::size_t inFlight() const override {
    std::lock_guard lock(mu_);
    return inFlight_;
  }
  SourceCounters counters() const override {
    std::lock_guard lock(mu_);
    return counters_;
  }

  // ---- test side ----
  struct Started {
    RequestId id;
    std::string path;
  };
  std::vector<Started> started() const {
    std::lock_guard lock(mu_);
    return started_;
  }
  std::vector<RequestId> cancels() const {
    std::lock_guard lock(mu_);
    return cancels_;
  }
  std::map<RequestId, std::string> held() const {
    std::lock_guard lock(mu_);
    std::map<RequestId, std::string> out;
    for (const auto& [id, h] : held_) out[id] = h.path;
    return out;
  }
  // Answers a held request (delivered on the source's thread). False if it is not held.
  bool reply(RequestId id, FetchResult r) {
    {
      std::lock_guard lock(mu_);
      auto it = held_.find(id);
      if (it == held_.end()) return false;
      r.id = id;
      queue_.push_back({std::move(it->second.done), std::move(r)});
      held_.erase(it);
    }
    cv_.notify_all();
    return true;
  }
  // Until every answer given so far has been delivered and its callback has returned.
  void waitDelivered() {
    std::unique_lock lock(mu_);
    cv_.wait(lock, [&] { return queue_.empty() && !delivering_; });
  }

  static FetchResult ok(std::vector<uint8_t> bytes) {
    FetchResult r;
    r.outcome = FetchOutcome::Ok;
    r.bytes = std::move(bytes);
    r.attempts = 1;
    return r;
  }
  static FetchResult outcome(FetchOutcome o, std::string message = "scripted") {
    FetchResult r;
    r.outcome = o;
    r.message = std::move(message);
    r.attempts = 1;
    return r;
  }

 private:
  struct Held {
    std::string path;
    FetchCallback done;
  };
  struct Delivery {
    FetchCallback done;
    FetchResult result;
  };
  static FetchResult cancelled(RequestId id) {
    FetchResult r = outcome(FetchOutcome::Cancelled);
    r.id = id;
    return r;
  }
  void run() {
    std::unique_lock lock(mu_);
    for (;;) {
      cv_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;
      Delivery d = std::move(queue_.front());
      queue_.pop_front();
      switch (d.result.outcome) {
        case FetchOutcome::Ok: ++counters_.requestsCompleted; break;
        case FetchOutcome::Missing: ++counters_.requestsMissing; break;
        case FetchOutcome::Failed: ++counters_.requestsFailed; break;
        case FetchOutcome::Cancelled: ++counters_.requestsCancelled; break;
      }
      delivering_ = true;
      lock.unlock();
      d.done(std::move(d.result));
      lock.lock();
      delivering_ = false;
      --inFlight_;
      cv_.notify_all();
    }
  }

  Script script_;
  mutable std::mutex mu_;
  std::condition_variable cv_;
  std::deque<Delivery> queue_;
  std::map<RequestId, Held> held_;
  std::map<std::string, int> attempts_;
  std::vector<Started> started_;
  std::vector<RequestId> cancels_;
  SourceCounters counters_;
  std::size_t inFlight_ = 0;
  bool delivering_ = false;
  bool stopping_ = false;
  std::thread thread_;  // last: starts after every member above exists
};

}  // namespace vegstream::streaming::test
