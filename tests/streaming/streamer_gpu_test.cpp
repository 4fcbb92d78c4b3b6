// TileStreamer's GPU side (imagery slots: byte budget per frame, slot count, LRU eviction, the
// slot reuse delay, CPU eviction of GPU tiles) and a whole settle over the real Zion import
// (JPEG imagery) checked against the tile codec.

#include <gtest/gtest.h>

#include <set>

#include "datasets/tile_codec.h"
#include "streaming/local_tile_source.h"
#include "streaming_fixture.h"

namespace vegstream::streaming::test {
namespace {

constexpr uint64_t kSlotBytes = 256 * 256 * 4;

using StreamerGpu = SyntheticDataset;

TEST_F(StreamerGpu, SlotCountIsTheSmallerOfBudgetAndDeviceLimit) {
  auto source = std::make_shared<LocalTileSource>(dir());
  StreamingOptions o;
  o.decodeThreads = 1;
  o.gpuBudgetBytes = 10 * kSlotBytes + 1000;
  EXPECT_EQ(TileStreamer(source, meta(), o, makeNullLogger()).gpuSlotCount(), 10u);
  o.maxGpuSlots = 3;
  EXPECT_EQ(TileStreamer(source, meta(), o, makeNullLogger()).gpuSlotCount(), 3u);
}

TEST_F(StreamerGpu, UploadsRespectByteBudgetSlotCountAndReuseDelay) {
  auto source = std::make_shared<LocalTileSource>(dir());
  StreamingOptions o;
  o.decodeThreads = 2;
  o.gpuBudgetBytes = 4 * kSlotBytes;
  o.slotReuseDelayFrames = 2;
  TileStreamer s(source, meta(), o, makeNullLogger());
  ASSERT_EQ(s.gpuSlotCount(), 4u);
  const auto keys = tilesAt(dir(), meta(), TileLayer::Imagery, meta().maxZoom);
  ASSERT_GE(keys.size(), 9u);
  const std::vector<TileKey> first(keys.begin(), keys.begin() + 5), second(keys.begin() + 5, keys.begin() + 9);
  auto all = wantsOf(first);
  const auto w2 = wantsOf(second);
  all.insert(all.end(), w2.begin(), w2.end());
  s.settle(all, 0.0);  // all nine on the CPU

  // Frame: budget 2 slots → the two highest-priority wants.
  const auto wantsA = wantsOf(first);
  s.update(wantsA, 1.0);
  auto up = s.planUploads(2 * kSlotBytes + 10);
  ASSERT_EQ(up.size(), 2u);
  EXPECT_EQ(up[0].tile->key, first[0]);
  EXPECT_EQ(up[1].tile->key, first[1]);
  EXPECT_EQ(s.state(first[0]), TileState::Uploading);
  EXPECT_EQ(s.frameStats().uploadBytes, 2 * kSlotBytes);
  s.uploadsRecorded(up);
  EXPECT_EQ(s.state(first[0]), TileState::ResidentGpu);
  EXPECT_EQ(s.findGpuResident(first[1]).slot, up[1].slot);
  // Next frame, default budget (8 MiB): only 2 slots are left for the 3 others.
  s.update(wantsA, 1.1);
  up = s.planUploads();
  ASSERT_EQ(up.size(), 2u);
  s.uploadsRecorded(up);
  EXPECT_EQ(s.frameStats().tilesResidentGpu, 4u);
  EXPECT_EQ(s.frameStats().bytesResidentGpu, 4 * kSlotBytes);
  // Every slot holds a tile used this frame: nothing is evicted, nothing uploaded.
  s.update(wantsA, 1.2);
  EXPECT_TRUE(s.planUploads().empty());
  EXPECT_EQ(s.frameStats().evictionsGpu, 0u);

  // Other wants: the four GPU tiles are not used any more and are evicted, but their slots are
  // reused only two frames later.
  const auto wantsB = wantsOf(second);
  std::set<uint32_t> slotsOfA;
  for (const auto& k : first)
    if (s.state(k) == TileState::ResidentGpu) slotsOfA.insert(s.findGpuResident(k).slot);
  ASSERT_EQ(slotsOfA.size(), 4u);
  s.update(wantsB, 2.0);
  EXPECT_TRUE(s.planUploads().empty());
  EXPECT_EQ(s.frameStats().evictionsGpu, 4u);
  EXPECT_EQ(s.frameStats().tilesResidentGpu, 0u);
  s.update(wantsB, 2.1);
  EXPECT_TRUE(s.planUploads().empty());  // one frame later: still cooling
  s.update(wantsB, 2.2);
  up = s.planUploads();
  ASSERT_EQ(up.size(), 4u);
  for (const auto& u : up) {
    EXPECT_TRUE(slotsOfA.contains(u.slot));
    EXPECT_LT(u.slot, s.gpuSlotCount());
  }
  s.uploadsRecorded(up);
  EXPECT_LE(s.frameStats().bytesResidentGpu, o.gpuBudgetBytes);
  EXPECT_EQ(s.state(first[0]), TileState::ResidentCpu);  // evicted from the GPU only
}

TEST_F(StreamerGpu, NonResidentWantUploadsItsNearestResidentAncestor) {
  auto source = std::make_shared<LocalTileSource>(dir());
  StreamingOptions o;
  o.decodeThreads = 1;
  TileStreamer s(source, meta(), o, makeNullLogger());
  const TileKey child = tilesAt(dir(), meta(), TileLayer::Imagery, meta().maxZoom)[0];
  const TileKey grandParent = parentOf(parentOf(child));
  s.settle(wantsOf({grandParent}), 0.0);
  s.update(wantsOf({child}), 0.1);  // child requested, not resident yet
  ASSERT_NE(s.state(child), TileState::ResidentCpu);
  const auto up = s.planUploads();
  ASSERT_EQ(up.size(), 1u);
  EXPECT_EQ(up[0].tile->key, grandParent);
  s.uploadsRecorded(up);
  const auto g = s.findGpuResident(child);
  ASSERT_TRUE(g.tile);
  EXPECT_EQ(g.levelsUp, 2);
  EXPECT_EQ(g.slot, up[0].slot);
}

TEST_F(StreamerGpu, CpuEvictionOfAGpuTileFreesItsSlot) {
  auto source = std::make_shared<LocalTileSource>(dir());
  StreamingOptions o;
  o.decodeThreads = 1;
  o.cpuBudgetBytes = 3 * (kSlotBytes + 256);
  o.slotReuseDelayFrames = 0;
  TileStreamer s(source, meta(), o, makeNullLogger());
  const auto keys = tilesAt(dir(), meta(), TileLayer::Imagery, meta().maxZoom);
  s.settle(wantsOf({keys[0], keys[1], keys[2]}), 0.0);
  s.uploadsRecorded(s.planUploads());
  EXPECT_EQ(s.frameStats().tilesResidentGpu, 3u);
  s.settle(wantsOf({keys[3], keys[4]}), 1.0);  // two new tiles push two old ones out of memory
  EXPECT_EQ(s.frameStats().tilesResidentCpu, 3u);
  EXPECT_EQ(s.state(keys[3]), TileState::ResidentCpu);
  EXPECT_EQ(s.state(keys[4]), TileState::ResidentCpu);
  EXPECT_LE(s.frameStats().bytesResidentCpu, o.cpuBudgetBytes);
  int onGpu = 0;
  for (int i = 0; i < 3; ++i) onGpu += s.state(keys[size_t(i)]) == TileState::ResidentGpu ? 1 : 0;
  EXPECT_EQ(onGpu, 1);
  EXPECT_EQ(s.frameStats().tilesResidentGpu, 1u);
}

using ZionStreaming = ZionDataset;

TEST_F(ZionStreaming, WholeRegionSettlesWithTheHeightsAndColoursOfTheCodec) {
  const auto& meta = this->meta();
  ASSERT_EQ(meta.imagery, datasets::ImageryFormat::Jpeg);
  auto source = std::make_shared<LocalTileSource>(dir());
  TileStreamer s(source, meta, StreamingOptions{}, makeNullLogger());
  auto keys = tilesAt(dir(), meta, TileLayer::Height, meta.maxZoom);
  const auto colour = tilesAt(dir(), meta, TileLayer::Imagery, meta.maxZoom);
  keys.insert(keys.end(), colour.begin(), colour.end());
  ASSERT_GE(keys.size(), 8u);
  s.settle(wantsOf(keys), 0.0);
  EXPECT_EQ(s.frameStats().wantedResident, keys.size());
  for (const auto& k : keys) {
    const auto tile = s.get(k);
    ASSERT_TRUE(tile) << toString(k);
    const fs::path file = dir() / datasetRelativePath(k, meta);
    if (k.layer == TileLayer::Height) {
      auto ref = datasets::readHeightTile(file, k.id, meta.elevationEncoding, datasets::kTileSize);
      ASSERT_TRUE(ref);
      size_t same = 0;
      for (size_t i = 0; i < ref->heights.size(); ++i)
        same += tile->heights->heights[i] == ref->heights[i] ||
                (std::isnan(tile->heights->heights[i]) && std::isnan(ref->heights[i]));
      EXPECT_EQ(same, ref->heights.size()) << toString(k);
    } else {
      auto ref = datasets::readColorTile(file, k.id, datasets::kTileSize);
      ASSERT_TRUE(ref);
      EXPECT_EQ(tile->colors->rgba, ref->rgba) << toString(k);
    }
  }
}

}  // namespace
}  // namespace vegstream::streaming::test
