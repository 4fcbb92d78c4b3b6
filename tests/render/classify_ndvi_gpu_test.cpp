// NDVI in the species choice (issue 18, item 4; vegetation/colour_score.h): the classify pass
// reads the imagery layer's NDVI (render/terrain_pass.h's R8 array) and scores it as a fourth
// channel, like the CPU reference. One colour, three NDVI zones: two species with the same
// reference colour — plants (NDVI 0.45) and bare shadowed rock (NDVI 0.1) — split a dark green
// evenly without NDVI; with it, the vegetated zone grows plants and the rock zone nothing, and
// a zone without NDVI (bytes 0) stays the even split.

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
  {"name": "plants", "reference": {"h_deg": 104, "s": 0.4, "v": 0.12, "ndvi": 0.45},
   "weights": {"h": 2, "s": 0.5, "v": 1, "ndvi": 3}, "p": 3, "kind": "grass",
   "height_m": {"min": 0.3, "max": 0.6}, "stiffness": {"min": 1, "max": 2},
   "width_m": {"min": 0.01, "max": 0.02}, "colour_modulation": {"min": 1, "max": 1}, "density_m2": 400},
  {"name": "shadowed rock", "reference": {"h_deg": 104, "s": 0.4, "v": 0.12, "ndvi": 0.1},
   "weights": {"h": 2, "s": 0.5, "v": 1, "ndvi": 3}, "p": 3, "bare": true}]})";

// West of x = 100: NDVI 0.45; 100 … 160: none (0); east of 160: 0.1.
std::vector<uint8_t> ndviMap() {
  std::vector<uint8_t> bytes(size_t{kTile} * kTile);
  for (uint32_t y = 0; y < kTile; ++y)
    for (uint32_t x = 0; x < kTile; ++x)
      bytes[size_t{y} * kTile + x] = x < 100 ? 185 /* 0.449 */ : x < 160 ? 0 : 141 /* 0.102 */;
  return bytes;
}

struct ZoneCounts {
  std::map<int, size_t> plants, all;  // groups of species 0 / items, per zone 0 … 2
};

class ClassifyNdviGpu : public GpuTest {};

TEST_F(ClassifyNdviGpu, NdviSeparatesPlantsFromShadowedRockOfTheSameColourAsTheCpuDoes) {
  const std::unique_ptr<Context> context = validatedContext();
  ASSERT_TRUE(context);
  const Context& ctx = *context;
  auto parsed = veg::parseSpeciesCatalog(kCatalog, "test catalog");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const veg::SpeciesCatalog& catalog = *parsed;

  // One dark green for the whole tile (sRGB of h 104°, s 0.4, v 0.12), with texel noise.
  std::vector<uint8_t> rgba(size_t{kTile} * kTile * 4);
  for (size_t i = 0; i < size_t{kTile} * kTile; ++i) {
    const int n = static_cast<int>(mix32(static_cast<uint32_t>(i)) % 5u) - 2;
    rgba[i * 4 + 0] = static_cast<uint8_t>(25 + n);
    rgba[i * 4 + 1] = static_cast<uint8_t>(31 + n);
    rgba[i * 4 + 2] = static_cast<uint8_t>(18 + n);
    rgba[i * 4 + 3] = 255;
  }
  const std::vector<uint8_t> ndvi = ndviMap();

  GpuImage imagery = createImageArray(ctx, {kTile, kTile}, 1, VK_FORMAT_R8G8B8A8_SRGB,
                                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "test imagery", 1,
                                      VK_FORMAT_R8G8B8A8_UNORM);
  GpuImage ndviImage = createImageArray(ctx, {kTile, kTile}, 1, VK_FORMAT_R8_UNORM,
                                        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "test NDVI");
  GpuBuffer staging = createBuffer(ctx, rgba.size() + ndvi.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                   MemoryUse::HostUpload, "test staging");
  std::memcpy(staging.mapped, rgba.data(), rgba.size());
  std::memcpy(static_cast<uint8_t*>(staging.mapped) + rgba.size(), ndvi.data(), ndvi.size());

  const vegstream::testing::ClassifyScene scene = vegstream::testing::makeClassifyScene(1, 6.0f);
  constexpr uint32_t kClusterSize = 8;
  ClassifyPass pass(ctx, ClassifyOptions{1u << 14});
  pass.setCatalog(catalog);
  const uint32_t capacity = pass.clustersPerSpecies();
  GpuBuffer recordsHost = createBuffer(ctx, VkDeviceSize{capacity} * kSpeciesSlots * sizeof(PlantClusterGpu),
                                       VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostReadback, "test records");
  // Groups of species 0 (plants) per zone, on the GPU, with and without the NDVI layer.
  const auto zoneOf = [&](uint32_t tri) {
    const float x = scene.gpu[tri].v0.x;
    return x < 96.0f ? 0 : (x > 104.0f && x < 154.0f) ? 1 : x > 164.0f ? 2 : -1;  // −1: a zone's edge
  };
  const ClassifyUploads uploads{imagery, ndviImage, staging, rgba.size()};
  const auto runGpu = [&](bool withNdvi) {  // the plants' groups (species 0)
    return classifyOnce(ctx, pass, uploads, scene.gpu, kClusterSize, withNdvi ? 1u : 0u, 1, recordsHost);
  };
  const auto gpuWith = runGpu(true), gpuWithout = runGpu(false);

  // The CPU reference with the same NDVI texels.
  const veg::ImageryTexels texels{rgba.data(), kTile, ndvi.data()};
  ClassifyGroups cpu;
  std::map<int, size_t> items;
  for (size_t i = 0; i < scene.cpu.size(); ++i) {
    const SeedTriangleGpu& t = scene.gpu[i];
    const veg::BaseColourAt ground = [&](glm::vec2 r) -> veg::GroundSample {
      const glm::vec2 uv0(t.uv01.x, t.uv01.y), uv1(t.uv01.z, t.uv01.w);
      const glm::vec2 uv = uv0 + r.x * (uv1 - uv0) + r.y * (t.uv2 - uv0);
      return {veg::sampleImageryLinear(texels, uv), veg::sampleImageryNdvi(texels, uv)};
    };
    std::vector<veg::PlantCluster> groups;
    veg::classifyTriangle(scene.cpu[i], static_cast<uint32_t>(i), catalog, {kClusterSize}, ground, groups);
    for (const veg::PlantCluster& g : groups) cpu[{g.triangle, g.cluster, g.firstSeed}] = g.species;
    items[zoneOf(static_cast<uint32_t>(i))] += veg::classifyItems(scene.cpu[i].plantCount, kClusterSize);
  }

  // GPU and CPU agree group for group (the scores are far from any tie: no precision cases).
  EXPECT_EQ(gpuWith, cpu);
  std::map<int, size_t> with, without;
  for (const auto& [k, v] : gpuWith) ++with[zoneOf(std::get<0>(k))];
  for (const auto& [k, v] : gpuWithout) ++without[zoneOf(std::get<0>(k))];
  std::printf("plants' share of work items per zone (vegetated, no NDVI, rock): with NDVI %.3f %.3f %.3f, without "
              "%.3f %.3f %.3f\n",
              double(with[0]) / double(items[0]), double(with[1]) / double(items[1]), double(with[2]) / double(items[2]),
              double(without[0]) / double(items[0]), double(without[1]) / double(items[1]),
              double(without[2]) / double(items[2]));
  ASSERT_GT(items[0], 500u);
  ASSERT_GT(items[2], 500u);
  // Without NDVI the two species tie everywhere: about half the groups grow plants.
  for (int zone : {0, 1, 2}) {
    EXPECT_NEAR(double(without[zone]) / double(items[zone]), 0.5, 0.1) << "zone " << zone;
  }
  // With it: nearly all in the vegetated zone, none on the rock, the zone without NDVI unchanged.
  EXPECT_GT(double(with[0]) / double(items[0]), 0.95);
  EXPECT_LT(double(with[2]) / double(items[2]), 0.02);
  EXPECT_EQ(with[1], without[1]);
}

}  // namespace
}  // namespace vegstream::render::testing
