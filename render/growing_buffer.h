#pragma once
// A per-frame-slot GPU buffer that grows ahead of need. Once a frame needs more than half of it,
// the next size (twice that need, up to a ceiling) is made on a worker (a TaskRunner), and the
// frame that outgrows the buffer takes the one made: making a buffer is an allocation the
// driver fills, 0.3 ms for 256 KiB … 7 ms for 256 MiB of device memory on the H200, and made on
// the frame thread it was the CPU frame's longest stall while the plants came in (three frames
// running, one per slot, at every doubling). Without a runner, or when the worker has not got to
// it, the frame makes it itself (or waits for the worker already making it), as before.
//
// Contents do not carry over: the passes that use it rewrite it every frame. Frame thread only;
// the destructor waits for a buffer being made (a queued one is never made).

#include <functional>
#include <memory>
#include <string>

#include "core/task_runner.h"
#include "render/gpu_resources.h"

namespace vegstream::render {

class GrowingBuffer {
 public:
  using Retire = std::function<void(GpuBuffer&&)>;
  // For ensure(): no ceiling (small enough that twice a need never overflows).
  static constexpr VkDeviceSize kNoCeiling = ~VkDeviceSize{0} / 4;

  GrowingBuffer() = default;
  // `minimum`: the smallest size made (grownSize's start: sizes are it doubled).
  GrowingBuffer(const Context& ctx, VkBufferUsageFlags usage, MemoryUse use, std::string name, TaskRunner* tasks,
                VkDeviceSize minimum = 64 * 1024);
  ~GrowingBuffer();
  GrowingBuffer(GrowingBuffer&&) = default;
  GrowingBuffer& operator=(GrowingBuffer&&) = default;

  // Holds at least min(bytes, ceiling) bytes when it returns (never more than max(ceiling,
  // bytes)); a buffer it replaces goes to `retire` (the frames in flight may still read it).
  // True when the buffer is a new one (descriptors must be written again).
  bool ensure(VkDeviceSize bytes, VkDeviceSize ceiling, const Retire& retire);

  const GpuBuffer& buffer() const { return buffer_; }
  VkBuffer get() const { return buffer_.get(); }
  VkDeviceSize size() const { return buffer_.size; }
  // Figures (tests): buffers made on the calling thread, and made by a worker and taken.
  int madeHere() const { return madeHere_; }
  int takenAhead() const { return takenAhead_; }

 private:
  struct Ahead;  // a buffer being made on the worker
  GpuBuffer make(VkDeviceSize size) const;
  GpuBuffer takeAhead();  // waits for (or makes) the one being made; empty if it failed
  void dropAhead(const Retire& retire);  // the one being made is not wanted

  const Context* ctx_ = nullptr;
  VkBufferUsageFlags usage_ = 0;
  MemoryUse use_ = MemoryUse::DeviceLocal;
  std::string name_;
  TaskRunner* tasks_ = nullptr;
  VkDeviceSize minimum_ = 64 * 1024;
  GpuBuffer buffer_;
  std::shared_ptr<Ahead> ahead_;
  int madeHere_ = 0, takenAhead_ = 0;
};

// Grows `b` to hold `bytes` like ensure() (no ceiling), keeping its first `validBytes`: for a pool
// that frames write in part and read whole. When a new buffer replaces the old one, `cmd` copies
// them across, after every earlier copy or compute write and before any later compute access.
// True when the buffer is a new one.
bool ensureKeeping(GrowingBuffer& b, VkCommandBuffer cmd, VkDeviceSize bytes, VkDeviceSize validBytes,
                   const GrowingBuffer::Retire& retire);

}  // namespace vegstream::render
