#pragma once
// GpuSlotAllocator (internal to the streamer): layers of the renderer's imagery array. A slot
// released at frame N may still be read by frames in flight, so it is handed out again only from
// frame N + reuseDelayFrames.

#include <cassert>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

namespace vegstream::streaming::detail {

class GpuSlotAllocator {
 public:
  GpuSlotAllocator(uint32_t count, int reuseDelayFrames) : count_(count), delay_(uint64_t(reuseDelayFrames)) {
    assert(reuseDelayFrames >= 0);
    free_.reserve(count);
    for (uint32_t s = count; s > 0; --s) free_.push_back(s - 1);  // slot 0 handed out first
  }

  uint32_t count() const { return count_; }
  uint32_t inUse() const { return count_ - uint32_t(free_.size()) - uint32_t(cooling_.size()); }
  // Released, not yet reusable.
  uint32_t cooling() const { return uint32_t(cooling_.size()); }

  // A free slot at `frame`, if any.
  std::optional<uint32_t> acquire(uint64_t frame) {
    while (!cooling_.empty() && cooling_.front().releasedAt + delay_ <= frame) {
      free_.push_back(cooling_.front().slot);
      cooling_.pop_front();
    }
    if (free_.empty()) return std::nullopt;
    const uint32_t s = free_.back();
    free_.pop_back();
    return s;
  }
  // Free slots at `frame` without taking one.
  uint32_t available(uint64_t frame) const {
    uint32_t n = uint32_t(free_.size());
    for (const auto& c : cooling_) n += c.releasedAt + delay_ <= frame ? 1u : 0u;
    return n;
  }

  void release(uint32_t slot, uint64_t frame) {
    assert(slot < count_);
    cooling_.push_back({slot, frame});  // frames only grow, so the deque stays in release order
  }

 private:
  struct Cooling {
    uint32_t slot;
    uint64_t releasedAt;
  };
  uint32_t count_;
  uint64_t delay_;
  std::vector<uint32_t> free_;
  std::deque<Cooling> cooling_;
};

}  // namespace vegstream::streaming::detail
