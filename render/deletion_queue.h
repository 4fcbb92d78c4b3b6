#pragma once
// Deferred destruction: an object released while frames up to F may still use it is
// destroyed only once frame F has completed on the GPU. Frames complete in submission order on
// the one queue, so one "last completed frame" number decides what can go.

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <type_traits>

namespace vegstream::render {

class DeletionQueue {
 public:
  // Keeps `owner` alive until frame `lastUse` has completed.
  template <typename T>
  void defer(uint64_t lastUse, T&& owner) {
    auto held = std::make_shared<std::decay_t<T>>(std::forward<T>(owner));
    entries_.push_back({lastUse, [held]() mutable { held.reset(); }});
  }

  // Destroys everything whose last use is at or before `completedFrame`.
  void collect(uint64_t completedFrame) {
    while (!entries_.empty() && entries_.front().lastUse <= completedFrame) {
      entries_.front().destroy();
      entries_.pop_front();
    }
  }

  // After vkDeviceWaitIdle: everything may go.
  void collectAll() { collect(UINT64_MAX); }
  size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    uint64_t lastUse;
    std::function<void()> destroy;
  };
  std::deque<Entry> entries_;  // lastUse is non-decreasing: entries are deferred in frame order
};

}  // namespace vegstream::render
