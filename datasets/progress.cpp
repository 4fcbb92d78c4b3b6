// The import progress reporter (progress.h): a redrawn bar on a terminal, plain lines in logs,
// and a one-line summary.

#include "datasets/progress.h"

#include <unistd.h>

#include <algorithm>

namespace vegstream::datasets {
namespace {

using Clock = std::chrono::steady_clock;

std::string formatBytes(uint64_t bytes) {
  char buf[32];
  if (bytes >= 1024ull * 1024ull)
    std::snprintf(buf, sizeof(buf), "%.1f MB", static_cast<double>(bytes) / 1048576.0);
  else
    std::snprintf(buf, sizeof(buf), "%.1f kB", static_cast<double>(bytes) / 1024.0);
  return buf;
}

std::string formatDuration(double s) {
  char buf[32];
  if (s < 60)
    std::snprintf(buf, sizeof(buf), "%.0fs", s);
  else
    std::snprintf(buf, sizeof(buf), "%dm%02ds", static_cast<int>(s / 60), static_cast<int>(s) % 60);
  return buf;
}

}  // namespace

void CallbackProgress::addTotal(uint64_t tiles) {
  std::lock_guard lock(mutex_);
  total_ += tiles;
  if (fn_) fn_(done_, total_);
}

void CallbackProgress::tileDone(uint64_t) {
  std::lock_guard lock(mutex_);
  ++done_;
  if (fn_) fn_(done_, std::max(done_, total_));
}

ProgressReporter::ProgressReporter(std::string label, std::FILE* out, int interactive)
    : label_(std::move(label)), out_(out),
      interactive_(interactive < 0 ? ::isatty(::fileno(out)) != 0 : interactive != 0), start_(Clock::now()),
      lastDraw_(start_) {}

double ProgressReporter::seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

void ProgressReporter::addTotal(uint64_t tiles) { total_ += tiles; }

void ProgressReporter::tileDone(uint64_t bytes) {
  ++done_;
  bytes_ += bytes;
  draw(false);
}

void ProgressReporter::stage(const std::string& name) {
  {
    std::lock_guard lock(drawMutex_);
    stage_ = name;
  }
  draw(true);
}

void ProgressReporter::draw(bool force) {
  std::unique_lock lock(drawMutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;  // another worker is drawing: skip, the next tile redraws
  const auto now = Clock::now();
  const double sinceDraw = std::chrono::duration<double>(now - lastDraw_).count();
  if (!force && sinceDraw < (interactive_ ? 0.1 : 5.0)) return;
  lastDraw_ = now;
  const uint64_t done = done_.load(), total = std::max(done, total_.load());
  const double elapsed = seconds();
  const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0.0;
  const double eta = rate > 0 ? static_cast<double>(total - done) / rate : 0.0;
  const double frac = total ? static_cast<double>(done) / static_cast<double>(total) : 0.0;
  if (interactive_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(frac * kWidth);
    std::string bar(static_cast<size_t>(filled), '#');
    bar.append(static_cast<size_t>(kWidth - filled), '-');
    std::fprintf(out_, "\r%s %s [%s] %llu/%llu tiles %3.0f%%  %.0f tiles/s  ETA %s   ", label_.c_str(), stage_.c_str(),
                 bar.c_str(), static_cast<unsigned long long>(done), static_cast<unsigned long long>(total),
                 100.0 * frac, rate, formatDuration(eta).c_str());
    drewBar_ = true;
  } else {
    std::fprintf(out_, "%s %s: %llu/%llu tiles (%.0f%%), %.0f tiles/s, ETA %s\n", label_.c_str(), stage_.c_str(),
                 static_cast<unsigned long long>(done), static_cast<unsigned long long>(total), 100.0 * frac, rate,
                 formatDuration(eta).c_str());
  }
  std::fflush(out_);
}

std::string ProgressReporter::finish() {
  if (interactive_ && drewBar_) draw(true);  // the bar's last state: done/total
  std::lock_guard lock(drawMutex_);
  const double s = seconds();
  const uint64_t done = done_.load();
  char buf[256];
  std::snprintf(buf, sizeof(buf), "%s: %llu tiles, %s, %.2f s (%.0f tiles/s)", label_.c_str(),
                static_cast<unsigned long long>(done), formatBytes(bytes_.load()).c_str(), s,
                s > 0 ? static_cast<double>(done) / s : 0.0);
  if (drewBar_) std::fprintf(out_, "\n");
  std::fflush(out_);
  drewBar_ = false;
  return buf;
}

}  // namespace vegstream::datasets
