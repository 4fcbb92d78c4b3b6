// The tree impostors kept between processes (render/impostor_atlas_cache.h), on lavapipe with
// validation on: a renderer that captures a conifer's and a broadleaf's impostors stores them; a
// second renderer, with its own handle on the same directory as a new process would have, reads
// them back instead of capturing — every level of every model's albedo atlas the same bytes, a
// frame of the two trees drawn as impostors (their normals and depths lit and shadowed) the same
// bytes, as is the frame of a renderer without the cache, and the trees' GPU bytes the same.
// Another model is another key: captured and stored beside the first. The file format's own
// checks are impostor_atlas_file_test.cpp's; a damaged entry met by the program,
// tests/app/snapshot_command_test.cpp's.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/log.h"
#include "gpu_test_fixture.h"
#include "lone_tree.h"
#include "render/tree_impostors.h"
#include "streaming/disk_tile_cache.h"
#include "tests/support/test_dirs.h"

namespace vegstream::render::testing {
namespace {
namespace fs = std::filesystem;

constexpr uint32_t kW = 160, kH = 90;
constexpr uint32_t kSeed = 0x2545f491u;

std::vector<TreeModelSet> twoModels(float conifer = 15.0f) {
  return {firstTreeOfForm(vegetation::TreeForm::Conifer, conifer, 5.0f),
          firstTreeOfForm(vegetation::TreeForm::Broadleaf, 12.0f, 9.0f)};
}

std::unique_ptr<streaming::DiskTileCache> openCache(const fs::path& dir) {
  auto c = streaming::DiskTileCache::open(dir, uint64_t{1} << 30, makeNullLogger());
  EXPECT_TRUE(c.ok()) << (c.ok() ? "" : c.error().message);
  return c.ok() ? std::move(*c) : nullptr;
}

size_t entries(const fs::path& dir) {
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().extension() == ".vsimpat";
  return n;
}

class ImpostorCacheTest : public GpuTest {
 protected:
  // A renderer of kW × kH, MSAA 4, with `sets` as its models, through `cache` (may be null).
  std::unique_ptr<Renderer> renderer(streaming::DiskTileCache* cache, const std::vector<TreeModelSet>& sets) {
    RendererOptions o = options(kW, kH, 4);
    o.impostorCache = cache;
    auto r = Renderer::create(o);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    if (!r.ok()) return nullptr;
    EXPECT_TRUE((*r)->setImageryLayers(1).ok());
    EXPECT_TRUE((*r)->setTreeModels(sets).ok());
    return std::move(*r);
  }

  // Every level of every model's albedo atlas, one after another.
  static std::vector<uint8_t> albedo(Renderer& r, uint32_t models) {
    std::vector<uint8_t> all;
    for (uint32_t m = 0; m < models; ++m)
      for (uint32_t level = 0; level < kImpostorMipLevels; ++level) {
        auto a = r.readTreeImpostor(m, level);
        EXPECT_TRUE(a.ok());
        if (a.ok()) all.insert(all.end(), a->begin(), a->end());
      }
    return all;
  }

  // The two trees 70 and 80 m away, side by side, drawn as impostors, with the sun's shadows
  // (their casters are the impostors too).
  FrameResult farTrees(Renderer& r) {
    LoneTree scene(15.0f, 5.0f, kSeed);
    TreeInstanceGpu broadleaf = scene.trees[0];
    broadleaf.model = 1;
    broadleaf.heightM = 12.0f;
    broadleaf.crownM = 9.0f;
    broadleaf.position[0] = 12.0f;
    broadleaf.position[1] = 10.0f;
    scene.trees.push_back(broadleaf);
    Camera cam;
    cam.position = {4.0, -70.0, 9.0};
    cam.forward = glm::normalize(glm::dvec3(0.0, 1.0, -0.02));
    cam.verticalFovDeg = 25.0;
    cam.nearM = 0.5;
    const glm::dvec3 sun = glm::normalize(glm::dvec3(-0.5, -0.6, 0.62));
    // The first frame uploads the plane's tile.
    renderTreeFrame(r, cam, sun, scene.draw, &scene.upload, scene.trees, true, true, 0.0f, 0.0f);
    return renderTreeFrame(r, cam, sun, scene.draw, nullptr, scene.trees, true, true, 0.0f, 0.0f);
  }
};

TEST_F(ImpostorCacheTest, AStoredAtlasComesBackTheSameBitForBit) {
  const fs::path dir = vegstream::testing::testOutputDir() / "cache";
  auto cacheA = openCache(dir);
  ASSERT_TRUE(cacheA);
  auto a = renderer(cacheA.get(), twoModels());
  ASSERT_TRUE(a);
  const ImpostorCacheFigures fa = a->impostorCacheFigures();
  EXPECT_FALSE(fa.hit);
  EXPECT_TRUE(fa.stored);
  EXPECT_EQ(entries(dir), 1u);
  // The atlases are mostly empty background: zstd keeps them small.
  const uint64_t raw = TreeImpostors::pixelBytes(2);
  std::printf("two models: %.1f MB of atlases stored in %.1f MB (%.0f ms)\n", double(raw) / 1e6,
              double(fa.fileBytes) / 1e6, fa.ms);
  EXPECT_GT(fa.fileBytes, 1000u);
  EXPECT_LT(fa.fileBytes, raw / 2);

  // A new handle on the directory, as the next process opens it.
  auto cacheB = openCache(dir);
  ASSERT_TRUE(cacheB);
  auto b = renderer(cacheB.get(), twoModels());
  auto none = renderer(nullptr, twoModels());
  ASSERT_TRUE(b && none);
  EXPECT_TRUE(b->impostorCacheFigures().hit);
  EXPECT_FALSE(b->impostorCacheFigures().stored);
  EXPECT_EQ(b->impostorCacheFigures().fileBytes, fa.fileBytes);
  EXPECT_FALSE(none->impostorCacheFigures().hit || none->impostorCacheFigures().stored);
  // The same GPU memory either way (tree_gpu_bytes in recordings): the capture's own targets go.
  EXPECT_EQ(a->treeGpuBytes(), b->treeGpuBytes());
  EXPECT_EQ(a->treeGpuBytes(), none->treeGpuBytes());

  const std::vector<uint8_t> atlasA = albedo(*a, 2), atlasB = albedo(*b, 2);
  ASSERT_EQ(atlasA.size(), raw / 2);
  EXPECT_TRUE(atlasA == atlasB) << "every level of both models' albedo";

  const FrameResult frameA = farTrees(*a), frameB = farTrees(*b), frameNone = farTrees(*none);
  ASSERT_TRUE(frameA.color && frameB.color && frameNone.color && frameA.trees);
  EXPECT_EQ(frameA.trees->impostor, 2u) << "both trees drawn as impostors";
  EXPECT_TRUE(frameA.color->rgba == frameB.color->rgba);
  EXPECT_TRUE(frameA.color->rgba == frameNone.color->rgba);
}

TEST_F(ImpostorCacheTest, AnotherModelIsAnotherKey) {
  const fs::path dir = vegstream::testing::testOutputDir() / "cache";
  auto cache = openCache(dir);
  ASSERT_TRUE(cache);
  auto a = renderer(cache.get(), twoModels(15.0f));
  ASSERT_TRUE(a);
  EXPECT_TRUE(a->impostorCacheFigures().stored);
  // The conifer 16 m tall instead of 15: its vertices differ, so must its atlas.
  auto b = renderer(cache.get(), twoModels(16.0f));
  ASSERT_TRUE(b);
  EXPECT_FALSE(b->impostorCacheFigures().hit);
  EXPECT_TRUE(b->impostorCacheFigures().stored);
  EXPECT_EQ(entries(dir), 2u);
  EXPECT_FALSE(albedo(*a, 1) == albedo(*b, 1));
  // And the first models again: their own entry.
  auto c = renderer(cache.get(), twoModels(15.0f));
  ASSERT_TRUE(c);
  EXPECT_TRUE(c->impostorCacheFigures().hit);
  EXPECT_TRUE(albedo(*a, 2) == albedo(*c, 2));
}

}  // namespace
}  // namespace vegstream::render::testing
