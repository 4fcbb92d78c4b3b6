// Overflow thinning (vegetation/overflow_thinning.h) in the classify pass: when a species'
// buffer is under pressure, which groups shrink and go is decided by their view-independent
// priority, never by the order the GPU's threads append in — the same groups survive with the
// triangles submitted in reverse — and matches the CPU reference; a pass whose buffers overflow
// once sets a pressure (updateThinning) under which the next frame fits.

#include <algorithm>
#include <map>
#include <tuple>
#include <vector>

#include "gpu_test_fixture.h"
#include "render/classify_pass.h"
#include "render/context.h"
#include "tests/support/classify_scene.h"
#include "vegetation/overflow_thinning.h"
#include "vegetation/plant_seeding.h"
#include "vegetation/species_catalog.h"

namespace vegstream::render::testing {
namespace {

namespace veg = vegstream::vegetation;
constexpr uint32_t kTile = kImageryTileSize;
constexpr uint32_t kClusterSize = 8;

// A group by its ground identity (triangle key, cluster, first seed) → its fade.
using Groups = std::map<std::tuple<uint64_t, uint32_t, uint32_t, uint32_t>, float>;

class ClassifyThinningGpu : public GpuTest {
 protected:
  void SetUp() override {
    context = validatedContext();
    ASSERT_TRUE(context);
    maps = {vegstream::testing::classifyBaseMap(1), vegstream::testing::classifyBaseMap(2)};
    imagery = createImageArray(*context, {kTile, kTile}, 2, VK_FORMAT_R8G8B8A8_SRGB,
                               VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "test imagery", 1,
                               VK_FORMAT_R8G8B8A8_UNORM);
    const VkDeviceSize tileBytes = VkDeviceSize{kTile} * kTile * 4;
    GpuBuffer staging = createBuffer(*context, 2 * tileBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                     MemoryUse::HostUpload, "test staging");
    for (uint32_t l = 0; l < 2; ++l)
      std::memcpy(static_cast<uint8_t*>(staging.mapped) + l * tileBytes, maps[l].data(), tileBytes);
    context->submitAndWait([&](VkCommandBuffer cmd) {
      for (uint32_t l = 0; l < 2; ++l) recordImageUpload(cmd, staging, imagery, l, l * tileBytes);
    });
    scene = vegstream::testing::makeClassifyScene(2, 9.0f);
  }

  // Classifies `triangles` (the scene's, in some order) and returns the groups of every species.
  Groups classify(ClassifyPass& pass, const std::vector<SeedTriangleGpu>& triangles, VegetationFigures& f) {
    context->submitAndWait([&](VkCommandBuffer cmd) {
      f = pass.record(cmd, 0, triangles, kClusterSize, imagery.alternateView.get(), imagery.alternateView.get(), false,
                      3 * kClusterSize, 0, [](GpuBuffer&&) {});
    });
    pass.readFigures(0, f);
    const uint32_t capacity = pass.clustersPerSpecies();
    GpuBuffer host = createBuffer(*context, VkDeviceSize{capacity} * kSpeciesSlots * sizeof(PlantClusterGpu),
                                  VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback, "test records");
    context->submitAndWait([&](VkCommandBuffer cmd) {
      const VkBufferCopy all{0, 0, host.size};
      vkCmdCopyBuffer(cmd, pass.records(0), host.get(), 1, &all);
      hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    });
    Groups out;
    const auto* records = static_cast<const PlantClusterGpu*>(host.mapped);
    for (uint32_t s = 0; s < kSpeciesSlots; ++s)
      for (uint32_t i = 0; i < std::min(f.groups[s], capacity); ++i) {
        const PlantClusterGpu& g = records[size_t{s} * capacity + i];
        const SeedTriangleGpu& t = triangles[g.triangle];
        out[{(uint64_t{t.keyHi} << 32) | t.keyLo, g.cluster, g.firstSeed, s}] = g.fade;
      }
    return out;
  }

  std::vector<SeedTriangleGpu> reversed() const { return {scene.gpu.rbegin(), scene.gpu.rend()}; }

  std::unique_ptr<Context> context;
  std::vector<std::vector<uint8_t>> maps;
  GpuImage imagery;
  vegstream::testing::ClassifyScene scene;
};

TEST_F(ClassifyThinningGpu, UnderPressureTheSameGroupsShrinkAndGoInAnyOrderAsOnTheCpu) {
  const veg::SpeciesCatalog& catalog = veg::defaultSpeciesCatalog();
  ClassifyPass pass(*context, ClassifyOptions{1u << 14});
  pass.setCatalog(catalog);
  VegetationFigures free, thinned, thinnedReversed;
  const Groups all = classify(pass, scene.gpu, free);
  std::array<float, kSpeciesSlots> pressure{};
  pressure.fill(0.5f);
  pass.setThinning(pressure);
  const Groups kept = classify(pass, scene.gpu, thinned);
  const Groups keptReversed = classify(pass, reversed(), thinnedReversed);
  EXPECT_EQ(kept, keptReversed) << "the thinning must not depend on the order of the work";
  EXPECT_EQ(thinned.wanted, free.wanted);

  // The CPU reference with the same pressure.
  veg::SeedingOptions options{kClusterSize};
  options.thinning.fill(0.5f);
  size_t cpuGroups = 0, agree = 0, partial = 0;
  for (size_t i = 0; i < scene.cpu.size(); ++i) {
    std::vector<veg::PlantCluster> groups;
    veg::classifyTriangle(scene.cpu[i], static_cast<uint32_t>(i), catalog, options,
                          vegstream::testing::classifyColour(scene.gpu[i], maps), groups);
    for (const veg::PlantCluster& g : groups) {
      ++cpuGroups;
      const auto it = kept.find({scene.cpu[i].key, g.cluster, g.firstSeed, g.species});
      if (it != kept.end() && std::abs(it->second - g.fade) < 1e-5f) ++agree;
      if (g.fade < 0.99f && g.fade > 0.0f) ++partial;
    }
  }
  const size_t wanted = all.size();
  std::printf("thinning at pressure 0.5: %zu of %zu groups kept (GPU), %zu (CPU), %zu agree, %zu shrinking\n",
              kept.size(), wanted, cpuGroups, agree, partial);
  EXPECT_EQ(kept.size(), cpuGroups);
  EXPECT_GE(agree, cpuGroups - cpuGroups / 100);  // GPU-precision-sensitive species choices: under 1 %
  // (1 + b)(1 − p) = 0.625 of the groups stay, a band of them shrinking.
  EXPECT_NEAR(double(kept.size()) / double(wanted), 0.625, 0.05);
  EXPECT_GT(partial, wanted / 10);
  for (const auto& [key, fade] : kept) EXPECT_TRUE(all.count(key)) << "thinning only removes";
}

TEST_F(ClassifyThinningGpu, AnOverflowSetsAPressureUnderWhichTheNextFrameFits) {
  ClassifyPass pass(*context, ClassifyOptions{256});
  pass.setCatalog(veg::defaultSpeciesCatalog());
  VegetationFigures first, second, secondReversed;
  classify(pass, scene.gpu, first);
  ASSERT_TRUE(first.overflow) << "the scene must overflow 256 groups per species";
  pass.updateThinning(first);
  const Groups a = classify(pass, scene.gpu, second);
  const Groups b = classify(pass, reversed(), secondReversed);
  EXPECT_FALSE(second.overflow);
  EXPECT_EQ(a, b);
  for (size_t s = 0; s < kSpeciesSlots; ++s) {
    EXPECT_LE(second.groups[s], 256u);
    if (first.wanted[s] > 192) {
      EXPECT_GT(second.thinning[s], 0.0f) << "species " << s;
    }
    EXPECT_NEAR(second.thinning[s], veg::thinningPressure(first.wanted[s], 256), 1e-6f);
  }
}

}  // namespace
}  // namespace vegstream::render::testing
