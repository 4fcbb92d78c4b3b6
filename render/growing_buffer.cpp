// GrowingBuffer (growing_buffer.h): the next size made on a worker before a frame needs it.
// Whoever claims the work first — the worker, or the frame thread that needs the buffer (or is
// destroying it) before the worker started — makes it; the other waits or does nothing.

#include "render/growing_buffer.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <condition_variable>
#include <mutex>

namespace vegstream::render {

struct GrowingBuffer::Ahead {
  // What to make: copied here, so that a worker never reads the GrowingBuffer itself.
  const Context* ctx = nullptr;
  VkBufferUsageFlags usage = 0;
  MemoryUse use = MemoryUse::DeviceLocal;
  std::string name;
  VkDeviceSize size = 0;
  std::atomic<bool> claimed{false};
  std::mutex mu;
  std::condition_variable doneCv;
  bool done = false;
  GpuBuffer made;  // empty when making it failed (the frame thread then makes its own)

  void build() {
    GpuBuffer b;
    try {
      b = createBuffer(*ctx, size, usage, use, name);
    } catch (...) {  // out of memory, say: the frame thread tries again and reports it
    }
    std::lock_guard lock(mu);
    made = std::move(b);
    done = true;
    doneCv.notify_all();
  }
  void wait() {
    std::unique_lock lock(mu);
    doneCv.wait(lock, [&] { return done; });
  }
};

GrowingBuffer::GrowingBuffer(const Context& ctx, VkBufferUsageFlags usage, MemoryUse use, std::string name,
                             TaskRunner* tasks, VkDeviceSize minimum)
    : ctx_(&ctx), usage_(usage), use_(use), name_(std::move(name)), tasks_(tasks), minimum_(minimum) {}

GrowingBuffer::~GrowingBuffer() {
  if (!ahead_) return;
  // A worker that took it must be done with the device first; one that has not started never
  // will (the claim is taken here). What it made is destroyed here, on this thread.
  if (ahead_->claimed.exchange(true)) ahead_->wait();
  GpuBuffer drop = std::move(ahead_->made);
}

GpuBuffer GrowingBuffer::make(VkDeviceSize size) const {
  assert(ctx_ && "a default-constructed GrowingBuffer is given a context before use");
  return createBuffer(*ctx_, size, usage_, use_, name_);
}

void GrowingBuffer::dropAhead(const Retire& retire) {
  std::shared_ptr<Ahead> ahead = std::move(ahead_);
  if (!ahead->claimed.exchange(true)) return;  // never started: nothing made
  ahead->wait();
  if (ahead->made.buffer) retire(std::move(ahead->made));  // unused: retired like any other
}

GpuBuffer GrowingBuffer::takeAhead() {
  std::shared_ptr<Ahead> ahead = std::move(ahead_);
  const bool here = !ahead->claimed.exchange(true);
  if (here)
    ahead->build();  // no worker took it yet: made here
  else
    ahead->wait();
  if (ahead->made.buffer) ++(here ? madeHere_ : takenAhead_);
  return std::move(ahead->made);
}

bool GrowingBuffer::ensure(VkDeviceSize bytes, VkDeviceSize ceiling, const Retire& retire) {
  const VkDeviceSize need = std::max<VkDeviceSize>(std::min(bytes, ceiling), 1);
  bool changed = false;
  if (!buffer_.buffer || buffer_.size < need) {
    GpuBuffer next;
    if (ahead_ && ahead_->size >= need && ahead_->size <= std::max(ceiling, need))
      next = takeAhead();
    else if (ahead_)
      dropAhead(retire);  // outgrown before it was taken (or past a lowered ceiling)
    if (!next.buffer) {
      next = make(std::max(std::min(grownSize(need, minimum_), ceiling), need));
      ++madeHere_;
    }
    if (buffer_.buffer) retire(std::move(buffer_));
    buffer_ = std::move(next);
    changed = true;
  }
  // More than half used: the next size, made ahead on the worker.
  if (tasks_ && !ahead_ && 2 * need > buffer_.size && buffer_.size < ceiling) {
    const VkDeviceSize size = std::min(grownSize(2 * need, minimum_), ceiling);
    if (size > buffer_.size) {
      ahead_ = std::make_shared<Ahead>();
      ahead_->ctx = ctx_;
      ahead_->usage = usage_;
      ahead_->use = use_;
      ahead_->name = name_;
      ahead_->size = size;
      tasks_->post([ahead = ahead_] {
        if (!ahead->claimed.exchange(true)) ahead->build();
      });
    }
  }
  return changed;
}

bool ensureKeeping(GrowingBuffer& b, VkCommandBuffer cmd, VkDeviceSize bytes, VkDeviceSize validBytes,
                   const GrowingBuffer::Retire& retire) {
  VkBuffer old = VK_NULL_HANDLE;
  const bool grown = b.ensure(std::max<VkDeviceSize>(bytes, 1), GrowingBuffer::kNoCeiling, [&](GpuBuffer&& o) {
    old = o.get();
    retire(std::move(o));  // kept alive until this frame has finished with it
  });
  if (grown && old != VK_NULL_HANDLE && validBytes > 0) {
    // Earlier frames' writes into the old buffer, then this copy out of it; then this frame's
    // writes over ranges the old contents may have held.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                  VK_ACCESS_2_TRANSFER_READ_BIT);
    const VkBufferCopy all{0, 0, validBytes};
    vkCmdCopyBuffer(cmd, old, b.get(), 1, &all);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  }
  return grown;
}

}  // namespace vegstream::render
