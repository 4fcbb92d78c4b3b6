// GrowingBuffer (render/growing_buffer.h) on the device: the next size is made by the runner
// once more than half is used, and taken when a frame outgrows the buffer, so growing makes no
// buffer on the calling thread after the first; the calling thread makes it itself when no
// worker has got to it; a buffer outgrown before it was taken is retired, not leaked; one being
// made is finished (or never started) when the GrowingBuffer goes. Validation stays silent.

#include <future>
#include <vector>

#include <gtest/gtest.h>

#include "core/task_runner.h"
#include "render/growing_buffer.h"
#include "tests/render/gpu_test_fixture.h"

namespace vegstream::render::testing {
namespace {

class GrowingBufferTest : public GpuTest {
 protected:
  std::vector<GpuBuffer> retired;
  GrowingBuffer::Retire retire() {
    return [this](GpuBuffer&& b) { retired.push_back(std::move(b)); };
  }
};

constexpr VkDeviceSize kKiB = 1024;
constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

TEST_F(GrowingBufferTest, TheNextSizeIsMadeByTheRunnerAndTakenWhenOutgrown) {
  auto ctx = validatedContext();
  ASSERT_TRUE(ctx);
  ManualTaskRunner tasks;
  {
    GrowingBuffer b(*ctx, kUsage, MemoryUse::DeviceLocal, "test buffer", &tasks);
    EXPECT_TRUE(b.ensure(100 * kKiB, 4096 * kKiB, retire()));
    EXPECT_EQ(b.size(), 128 * kKiB);  // grownSize: 64 KiB doubled
    EXPECT_EQ(b.madeHere(), 1);
    EXPECT_EQ(tasks.runAll(), 1u) << "100 of 128 KiB used: the next size was queued";
    EXPECT_FALSE(b.ensure(120 * kKiB, 4096 * kKiB, retire())) << "it still fits";
    EXPECT_EQ(tasks.pending(), 0u) << "one made ahead at a time";
    EXPECT_TRUE(b.ensure(200 * kKiB, 4096 * kKiB, retire()));
    EXPECT_EQ(b.size(), 256 * kKiB) << "twice the 100 KiB that started it, grown";
    EXPECT_EQ(b.madeHere(), 1) << "taken, not made here";
    EXPECT_EQ(b.takenAhead(), 1);
    EXPECT_EQ(retired.size(), 1u);  // the 128 KiB one, for the frames still reading it
    // A need past the one being made (512 KiB): that one is retired, this thread makes its own.
    EXPECT_EQ(tasks.runAll(), 1u);
    EXPECT_TRUE(b.ensure(2000 * kKiB, 4096 * kKiB, retire()));
    EXPECT_EQ(b.size(), 2048 * kKiB);
    EXPECT_EQ(b.madeHere(), 2);
    EXPECT_EQ(retired.size(), 3u);  // the 256 KiB one and the unused 512 KiB one
    // Never past the ceiling: the 4 MiB one queued is dropped unmade.
    EXPECT_TRUE(b.ensure(3000 * kKiB, 3000 * kKiB, retire()));
    EXPECT_EQ(b.size(), 3000 * kKiB);
    EXPECT_EQ(b.madeHere(), 3);
    EXPECT_EQ(retired.size(), 4u);
    EXPECT_EQ(tasks.runAll(), 1u);  // the dropped one: runs, makes nothing
    EXPECT_FALSE(b.ensure(2900 * kKiB, 3000 * kKiB, retire()));
    EXPECT_EQ(tasks.pending(), 0u) << "at the ceiling: nothing more is made ahead";

    // No worker got to it: this thread makes it when it is needed.
    GrowingBuffer c(*ctx, kUsage, MemoryUse::HostUpload, "test buffer 2", &tasks);
    c.ensure(40 * kKiB, 4096 * kKiB, retire());
    EXPECT_EQ(tasks.pending(), 1u);
    c.ensure(100 * kKiB, 4096 * kKiB, retire());
    EXPECT_EQ(c.size(), 128 * kKiB);
    EXPECT_EQ(c.madeHere(), 2);
    EXPECT_EQ(c.takenAhead(), 0);
    EXPECT_NE(c.buffer().mapped, nullptr);
    // The claimed task does nothing; the next one (256 KiB) is made and stays with c.
    EXPECT_EQ(tasks.runAll(), 2u);
    EXPECT_EQ(c.size(), 128 * kKiB);

    // A minimum: the smallest size made, doubled from there.
    GrowingBuffer m(*ctx, kUsage, MemoryUse::DeviceLocal, "test buffer 4", nullptr, 1024 * kKiB);
    m.ensure(10 * kKiB, GrowingBuffer::kNoCeiling, retire());
    EXPECT_EQ(m.size(), 1024 * kKiB);
    m.ensure(1500 * kKiB, GrowingBuffer::kNoCeiling, retire());
    EXPECT_EQ(m.size(), 2048 * kKiB);

    // One queued when its buffer goes: the destructor claims it, so it is never made.
    GrowingBuffer d(*ctx, kUsage, MemoryUse::DeviceLocal, "test buffer 3", &tasks);
    d.ensure(50 * kKiB, 4096 * kKiB, retire());
    EXPECT_EQ(tasks.pending(), 1u);
  }
  EXPECT_EQ(tasks.runAll(), 1u);  // after d went: nothing made, the device untouched
  retired.clear();
}

TEST_F(GrowingBufferTest, OnAPoolAGrowingNeedIsMetByBuffersMadeAhead) {
  auto ctx = validatedContext();
  ASSERT_TRUE(ctx);
  ThreadPool pool(1);
  GrowingBuffer b(*ctx, kUsage, MemoryUse::DeviceLocal, "test buffer", &pool);
  // The need grows by 10 % a frame from 64 KiB to 16 MiB, as plants coming in do. Between
  // frames the worker gets through what was posted (one worker: tasks run in order, so a
  // marker posted after a frame runs after that frame's task).
  VkDeviceSize need = 64 * kKiB;
  for (int frame = 0; need < 16 * 1024 * kKiB; ++frame, need = need * 11 / 10) {
    b.ensure(need, 64 * 1024 * kKiB, retire());
    ASSERT_GE(b.size(), need) << "frame " << frame;
    std::promise<void> idle;
    pool.post([&] { idle.set_value(); });
    idle.get_future().wait();
  }
  EXPECT_EQ(b.madeHere(), 1) << "only the first: every later size was made ahead";
  EXPECT_EQ(b.takenAhead(), 8) << "128 KiB doubled to 16 MiB";
  retired.clear();
}

}  // namespace
}  // namespace vegstream::render::testing
