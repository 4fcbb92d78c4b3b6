#pragma once
// Shared by the HTTP source tests: a small synthetic dataset made once per test process (ctest
// runs each test in its own process, possibly in parallel, so the directory carries the pid),
// and small helpers to wait for callbacks.

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "core/log.h"
#include "datasets/progress.h"
#include "datasets/synthetic_generator.h"
#include "streaming/tile_source.h"

namespace vegstream::testing {

// VEGSTREAM_TEST_TMP/http_<name>_<pid>, empty.
inline std::filesystem::path httpTestTmp(const std::string& name) {
  const auto p = std::filesystem::path(VEGSTREAM_TEST_TMP) / ("http_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p;
}

// The source's in-flight count once every callback has returned: it drops just after the last
// callback (tile_source.h), so a test that has seen every result waits for it (up to 1 s).
inline std::size_t inFlightAfterCallbacks(const streaming::TileSource& source) {
  const auto limit = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  while (source.inFlight() > 0 && std::chrono::steady_clock::now() < limit)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return source.inFlight();
}

inline std::vector<uint8_t> fileBytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A 4 km synthetic dataset (a few dozen tiles), made once per process. A suite set-up that
// fails records why in setupError_ and every test fails in SetUp (GoogleTest would skip them).
class HttpDataset : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(setupError_.empty()) << setupError_; }
  static void SetUpTestSuite() {
    setupError_.clear();
    root_ = new std::filesystem::path(httpTestTmp("root"));
    datasets::SyntheticOptions o;
    o.out = *root_ / "synthetic";
    o.sizeKm = 4.0;
    o.threads = 2;
    datasets::NullProgress progress;
    auto meta = datasets::generateSyntheticDataset(o, makeNullLogger(), progress);
    if (!meta.ok()) {
      setupError_ = "synthetic dataset: " + meta.error().message;
      return;
    }
    meta_ = new datasets::DatasetMeta(*meta);
    tiles_ = new std::vector<std::string>;
    for (const auto& e : std::filesystem::recursive_directory_iterator(o.out))
      if (e.is_regular_file() && e.path().filename() != "dataset.json")
        tiles_->push_back(std::filesystem::relative(e.path(), o.out).generic_string());
    std::sort(tiles_->begin(), tiles_->end());
  }
  static void TearDownTestSuite() {
    std::filesystem::remove_all(*root_);
    delete root_;
    delete meta_;
    delete tiles_;
  }
  static std::filesystem::path dir() { return *root_ / "synthetic"; }
  static std::filesystem::path work() { return *root_; }
  static const datasets::DatasetMeta& meta() { return *meta_; }
  // Every tile file, relative to the dataset root ("elevation/13/4281/2913.png"), sorted.
  static const std::vector<std::string>& tiles() { return *tiles_; }
  static inline std::string setupError_;

 private:
  static inline std::filesystem::path* root_ = nullptr;
  static inline datasets::DatasetMeta* meta_ = nullptr;
  static inline std::vector<std::string>* tiles_ = nullptr;
};

// Collects callbacks (from any thread) and counts how often each request id was called back.
class Results {
 public:
  streaming::FetchCallback callback() {
    return [this](streaming::FetchResult&& r) {
      std::lock_guard lock(mutex_);
      ++calls_[r.id];
      results_.push_back(std::move(r));
      changed_.notify_all();
    };
  }
  // Waits until `n` callbacks have arrived; false on time-out.
  bool waitFor(size_t n, std::chrono::milliseconds timeout = std::chrono::seconds(20)) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] { return results_.size() >= n; });
  }
  std::vector<streaming::FetchResult> take() {
    std::lock_guard lock(mutex_);
    return results_;
  }
  std::optional<streaming::FetchResult> find(streaming::RequestId id) {
    std::lock_guard lock(mutex_);
    for (const auto& r : results_)
      if (r.id == id) return r;
    return std::nullopt;
  }
  // Every id in [first, first + n) called back exactly once, and nothing else.
  bool eachOnce(streaming::RequestId first, size_t n) {
    std::lock_guard lock(mutex_);
    if (calls_.size() != n) return false;
    for (streaming::RequestId id = first; id < first + n; ++id)
      if (calls_[id] != 1) return false;
    return true;
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<streaming::FetchResult> results_;
  std::map<streaming::RequestId, int> calls_;
};

}  // namespace vegstream::testing
