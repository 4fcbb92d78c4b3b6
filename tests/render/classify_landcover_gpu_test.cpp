// Landcover classes in the GPU's species choice (issue 41, item 2): the classify pass reads the
// class code of each imagery layer's companion texel (render/terrain_pass.h's RG8 array, G) and
// lets the catalog's landcoverCodes narrow the species, like the CPU reference
// (vegetation/plant_seeding.cpp with GroundSample::allowed). Two grasses of one reference colour
// split a meadow evenly by colour; across four class zones — one that allows only the first, no
// class (code 0), one that allows only the second, one that allows nothing (built-up) — the GPU
// agrees with the CPU group for group, and each zone grows what its class allows.

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <tuple>
#include <vector>

#include "classify_readback.h"
#include "gpu_test_fixture.h"
#include "render/classify_pass.h"
#include "render/context.h"
#include "tests/support/classify_scene.h"
#include "vegetation/imagery_texels.h"
#include "vegetation/plant_seeding.h"
#include "vegetation/species_catalog.h"

namespace vegstream::render::testing {
namespace {

namespace veg = vegstream::vegetation;
constexpr uint32_t kTile = kImageryTileSize;

constexpr const char* kCatalog = R"({"species": [
  {"name": "meadow", "reference": {"h_deg": 90, "s": 0.45, "v": 0.35},
   "weights": {"h": 2, "s": 0.5, "v": 1}, "p": 3, "kind": "grass",
   "height_m": {"min": 0.3, "max": 0.6}, "stiffness": {"min": 1, "max": 2},
   "width_m": {"min": 0.01, "max": 0.02}, "colour_modulation": {"min": 1, "max": 1}, "density_m2": 400},
  {"name": "sedge", "reference": {"h_deg": 90, "s": 0.45, "v": 0.35},
   "weights": {"h": 2, "s": 0.5, "v": 1}, "p": 3, "kind": "grass",
   "height_m": {"min": 0.3, "max": 0.6}, "stiffness": {"min": 1, "max": 2},
   "width_m": {"min": 0.01, "max": 0.02}, "colour_modulation": {"min": 1, "max": 1}, "density_m2": 400}]})";

// Class codes by texel column: < 64 grassland (30), < 128 none (0), < 192 bare (60), else built (50).
uint8_t codeAt(uint32_t x) { return x < 64 ? 30 : x < 128 ? 0 : x < 192 ? 60 : 50; }

std::array<veg::SpeciesMask, 256> masks() {
  std::array<veg::SpeciesMask, 256> m{};  // codes the "scheme" does not know: nothing
  m[0] = veg::kAllSpecies;
  m[30] = 1u;  // meadow only
  m[60] = 2u;  // sedge only
  m[50] = 0u;  // built-up: nothing
  return m;
}

using Groups = ClassifyGroups;  // group → species

class ClassifyLandcoverGpu : public GpuTest {};

TEST_F(ClassifyLandcoverGpu, ClassesNarrowTheChoiceAsOnTheCpu) {
  const std::unique_ptr<Context> context = validatedContext();
  ASSERT_TRUE(context);
  const Context& ctx = *context;
  auto parsed = veg::parseSpeciesCatalog(kCatalog, "test catalog");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  veg::SpeciesCatalog catalog = *parsed;
  catalog.landcoverCodes = masks();

  // One olive green (h 90°, s 0.45, v 0.35) with texel noise; companions RG8: no NDVI, the class.
  std::vector<uint8_t> rgba(size_t{kTile} * kTile * 4), companions(size_t{kTile} * kTile * 2);
  for (size_t i = 0; i < size_t{kTile} * kTile; ++i) {
    const int n = static_cast<int>(mix32(static_cast<uint32_t>(i)) % 5u) - 2;
    rgba[i * 4 + 0] = static_cast<uint8_t>(74 + n);
    rgba[i * 4 + 1] = static_cast<uint8_t>(89 + n);
    rgba[i * 4 + 2] = static_cast<uint8_t>(49 + n);
    rgba[i * 4 + 3] = 255;
    companions[i * 2 + 1] = codeAt(static_cast<uint32_t>(i % kTile));
  }
  GpuImage imagery = createImageArray(ctx, {kTile, kTile}, 1, VK_FORMAT_R8G8B8A8_SRGB,
                                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "test imagery", 1,
                                      VK_FORMAT_R8G8B8A8_UNORM);
  GpuImage companionImage = createImageArray(ctx, {kTile, kTile}, 1, VK_FORMAT_R8G8_UNORM,
                                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                             "test companions");
  GpuBuffer staging = createBuffer(ctx, rgba.size() + companions.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                   MemoryUse::HostUpload, "test staging");
  std::memcpy(staging.mapped, rgba.data(), rgba.size());
  std::memcpy(static_cast<uint8_t*>(staging.mapped) + rgba.size(), companions.data(), companions.size());

  const vegstream::testing::ClassifyScene scene = vegstream::testing::makeClassifyScene(1, 6.0f);
  constexpr uint32_t kClusterSize = 8;
  ClassifyPass pass(ctx, ClassifyOptions{1u << 14});
  pass.setCatalog(catalog);
  const uint32_t capacity = pass.clustersPerSpecies();
  GpuBuffer recordsHost = createBuffer(ctx, VkDeviceSize{capacity} * kSpeciesSlots * sizeof(PlantClusterGpu),
                                       VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback, "test records");
  const ClassifyUploads uploads{imagery, companionImage, staging, rgba.size()};
  const auto runGpu = [&](uint32_t flags) {
    return classifyOnce(ctx, pass, uploads, scene.gpu, kClusterSize, flags, 2, recordsHost);
  };
  const Groups gpuWith = runGpu(2u), gpuWithout = runGpu(0u);

  // The CPU reference: the class of the texel whose square holds the point.
  const veg::ImageryTexels texels{rgba.data(), kTile, nullptr};
  const std::array<veg::SpeciesMask, 256> m = masks();
  Groups cpu;
  std::map<int, size_t> items;
  const auto zoneOf = [&](uint32_t tri) {  // by the triangle's apex; −1 near a zone's edge
    const float x = scene.gpu[tri].v0.x;
    for (int z = 0; z < 4; ++z)
      if (x > 64.0f * float(z) + 4.0f && x < 64.0f * float(z + 1) - 4.0f) return z;
    return -1;
  };
  for (size_t i = 0; i < scene.cpu.size(); ++i) {
    const SeedTriangleGpu& t = scene.gpu[i];
    const veg::BaseColourAt ground = [&](glm::vec2 r) -> veg::GroundSample {
      const glm::vec2 uv0(t.uv01.x, t.uv01.y), uv1(t.uv01.z, t.uv01.w);
      const glm::vec2 uv = uv0 + r.x * (uv1 - uv0) + r.y * (t.uv2 - uv0);
      const auto x = static_cast<uint32_t>(std::clamp(std::floor(uv.x * float(kTile)), 0.0f, float(kTile - 1)));
      return {veg::sampleImageryLinear(texels, uv), veg::kNoNdvi, m[codeAt(x)]};
    };
    std::vector<veg::PlantCluster> groups;
    veg::classifyTriangle(scene.cpu[i], static_cast<uint32_t>(i), catalog, {kClusterSize}, ground, groups);
    for (const veg::PlantCluster& g : groups) cpu[{g.triangle, g.cluster, g.firstSeed}] = g.species;
    items[zoneOf(static_cast<uint32_t>(i))] += veg::classifyItems(scene.cpu[i].plantCount, kClusterSize);
  }
  EXPECT_EQ(gpuWith, cpu);

  std::map<int, std::array<size_t, 2>> with, without;
  for (const auto& [k, s] : gpuWith) ++with[zoneOf(std::get<0>(k))][s];
  for (const auto& [k, s] : gpuWithout) ++without[zoneOf(std::get<0>(k))][s];
  for (int z = 0; z < 4; ++z) {
    ASSERT_GT(items[z], 300u) << "zone " << z;
    std::printf("zone %d: %zu items; with classes meadow %zu sedge %zu, without %zu %zu\n", z, items[z], with[z][0],
                with[z][1], without[z][0], without[z][1]);
    // Without classes the two grasses tie: about half each, in every zone.
    EXPECT_NEAR(double(without[z][0]) / double(items[z]), 0.5, 0.1) << "zone " << z;
  }
  // Grassland: the meadow grass alone, on (nearly) every item (a few fade out by their count).
  EXPECT_GT(double(with[0][0]) / double(items[0]), 0.95);
  EXPECT_EQ(with[0][1], 0u);
  EXPECT_EQ(with[1], without[1]);  // no class: the colour alone, as without the layer
  EXPECT_EQ(with[2][0], 0u);  // bare: the sedge alone
  EXPECT_GT(double(with[2][1]) / double(items[2]), 0.95);
  EXPECT_EQ(with[3][0] + with[3][1], 0u);  // built-up: nothing grows
}

}  // namespace
}  // namespace vegstream::render::testing
