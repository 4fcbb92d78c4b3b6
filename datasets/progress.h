#pragma once
// Progress of a long import: how many tiles are done out of how many, the rate, the time left.
// On a terminal (stderr is a tty) a bar redrawn in place at most ~10 times a second; otherwise
// (logs, CI, tests) a plain line every few seconds. At the end, one summary line: tiles,
// bytes, seconds. Importers and the pyramid builder see only ProgressSink, so a caller that
// does not care passes NullProgress, and one with its own callback wraps it in CallbackProgress.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>

namespace vegstream::datasets {

// Thread-safe: workers call tileDone concurrently.
class ProgressSink {
 public:
  virtual ~ProgressSink() = default;
  // More work became known (a stage added its tiles). Called before those tiles are done.
  virtual void addTotal(uint64_t tiles) = 0;
  // One tile finished; `bytes` written for it (0 when the tile was empty and not written).
  virtual void tileDone(uint64_t bytes) = 0;
  // A new stage begins ("zoom 12", "pyramid"): shown beside the bar.
  virtual void stage(const std::string& /*name*/) {}
};

class NullProgress final : public ProgressSink {
 public:
  void addTotal(uint64_t) override {}
  void tileDone(uint64_t) override {}
};

// Forwards (done, total) to a function, e.g. XyzProgress. The function is called under a lock.
class CallbackProgress final : public ProgressSink {
 public:
  explicit CallbackProgress(std::function<void(uint64_t done, uint64_t total)> fn) : fn_(std::move(fn)) {}
  void addTotal(uint64_t tiles) override;
  void tileDone(uint64_t bytes) override;

 private:
  std::mutex mutex_;
  std::function<void(uint64_t, uint64_t)> fn_;
  uint64_t done_ = 0, total_ = 0;
};

// The bar / plain-line reporter of the command line. Writes to `out` (stderr by default).
class ProgressReporter final : public ProgressSink {
 public:
  // interactive: 1 bar, 0 plain lines, -1 = a bar exactly when isatty(fileno(out)).
  explicit ProgressReporter(std::string label, std::FILE* out = stderr, int interactive = -1);
  void addTotal(uint64_t tiles) override;
  void tileDone(uint64_t bytes) override;
  void stage(const std::string& name) override;

  // Ends the bar and prints "label: N tiles, X MB, S s (R tiles/s)". Returns that line.
  std::string finish();

  uint64_t tilesDone() const { return done_.load(); }
  uint64_t bytesWritten() const { return bytes_.load(); }
  double seconds() const;

 private:
  void draw(bool force);

  std::string label_;
  std::FILE* out_;
  bool interactive_;
  std::chrono::steady_clock::time_point start_;
  std::atomic<uint64_t> done_{0}, total_{0}, bytes_{0};
  std::mutex drawMutex_;
  std::chrono::steady_clock::time_point lastDraw_;
  std::string stage_;
  bool drewBar_ = false;
};

}  // namespace vegstream::datasets
