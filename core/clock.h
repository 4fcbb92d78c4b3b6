#pragma once
// Clock: where code on the frame path reads the time (seconds as double), injected so that tests
// drive time by hand (ManualClock) instead of sleeping, and so that nothing that must be
// reproducible (a settled recording) reads the wall clock by accident.
//
// SteadyClock: std::chrono::steady_clock, seconds since the clock was made. ManualClock: the time
// a test sets; any thread may read it while one thread sets it. Stopwatch (stopwatch.h) stays
// for measuring figures, which are allowed to differ from run to run.

#include <atomic>
#include <chrono>

namespace vegstream {

class Clock {
 public:
  virtual ~Clock() = default;
  virtual double nowS() const = 0;  // monotonic: never goes back
};

class SteadyClock final : public Clock {
 public:
  SteadyClock() : start_(std::chrono::steady_clock::now()) {}
  double nowS() const override {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

class ManualClock final : public Clock {
 public:
  explicit ManualClock(double startS = 0.0) : now_(startS) {}
  double nowS() const override { return now_.load(); }
  void set(double s) { now_.store(s); }
  void advance(double dS) { now_.store(now_.load() + dS); }  // one setting thread

 private:
  std::atomic<double> now_;
};

}  // namespace vegstream
