// The measurement AOVs (issue 39 item 7) without a GPU: the --aov list, the file names, the
// decoding of an AOV frame's read-back (render/aov_image.h) and the TIFFs written beside a still.

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "render/aov_image.h"
#include "render/frame_types.h"
#include "scene/frame_aovs.h"
#include "tests/support/test_dirs.h"

namespace vegstream {
namespace {
namespace fs = std::filesystem;

TEST(FrameAovs, ParsesTheListAndNamesWhatIsWrong) {
  auto all = scene::parseAovList("depth,coverage,species");
  ASSERT_TRUE(all.ok());
  EXPECT_TRUE(all->depth && all->coverage && all->species);
  auto one = scene::parseAovList("coverage");
  ASSERT_TRUE(one.ok());
  EXPECT_TRUE(!one->depth && one->coverage && !one->species);
  auto none = scene::parseAovList("");
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->any());
  for (const char* bad : {"depth,normals", "Depth", "depth,,species", "depth,", "depth,depth"}) {
    auto r = scene::parseAovList(bad, "--aov");
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
    EXPECT_EQ(r.error().message.rfind(std::string("--aov ") + bad + ":", 0), 0u) << r.error().message;
  }
  EXPECT_EQ(scene::aovPathFor("/a/b/still.png", "depth"), fs::path("/a/b/still.depth.tif"));
}

// A 2 × 2 AOV frame: sky, bare ground, a pixel half covered by species 3, one fully by species 0.
TEST(FrameAovs, DecodesCoverageSpeciesAndDistance) {
  render::Camera camera;
  camera.verticalFovDeg = 60.0;
  camera.nearM = 0.5;
  camera.farM = 1000.0;
  const glm::dmat4 proj = render::projection(camera, 1.0);
  const glm::dmat4 inv = glm::inverse(proj);
  // The depth of a point straight along each pixel's centre ray at `metres` from the camera.
  auto depthAt = [&](uint32_t x, uint32_t y, double metres) {
    const glm::dvec4 ndc((2.0 * x + 1.0) / 2.0 - 1.0, (2.0 * y + 1.0) / 2.0 - 1.0, 0.5, 1.0);
    glm::dvec4 v = inv * ndc;
    const glm::dvec3 dir = glm::normalize(glm::dvec3(v) / v.w);
    const glm::dvec4 clip = proj * glm::dvec4(dir * metres, 1.0);
    return float(clip.z / clip.w);
  };
  const std::vector<float> depth = {0.0f, depthAt(1, 0, 12.0), depthAt(0, 1, 40.0), depthAt(1, 1, 3.0)};
  // The colour target's packed floats (render_targets.h), as the read-back holds them.
  const auto p = [](float r, float g) { return glm::packF2x11_1x10(glm::vec3(r, g, 0.0f)); };
  const std::vector<uint32_t> packed = {p(0, 0), p(0, 0), p(0.5f * 4.0f, 0.5f), p(1.0f, 1.0f)};
  const render::AovImage a = render::decodeAov(2, 2, packed.data(), depth.data(), inv);
  EXPECT_EQ(a.distanceM[0], 0.0f);
  EXPECT_NEAR(a.distanceM[1], 12.0, 1e-3);
  EXPECT_NEAR(a.distanceM[2], 40.0, 1e-2);
  EXPECT_NEAR(a.distanceM[3], 3.0, 1e-3);
  EXPECT_EQ(a.coverage, (std::vector<float>{0.0f, 0.0f, 0.5f, 1.0f}));
  EXPECT_EQ(a.species, (std::vector<float>{0.0f, 0.0f, 4.0f, 1.0f}));
}

TEST(FrameAovs, WritesTheSelectedFloatTiffsBesideTheStill) {
  const fs::path png = testing::testOutputDir() / "still.png";
  render::AovImage a;
  a.width = 3;
  a.height = 2;
  a.distanceM = {0.0f, 1.5f, 2.5f, 100.0f, 1e4f, 7.25f};
  a.coverage = {0.0f, 0.25f, 1.0f, 0.5f, 0.75f, 1.0f};
  a.species = {0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f};
  scene::AovSelection which;
  which.depth = which.species = true;
  ASSERT_TRUE(scene::writeFrameAovs(png, a, which).ok());
  EXPECT_FALSE(fs::exists(scene::aovPathFor(png, "coverage")));
  for (const auto& [name, values] : {std::pair{"depth", a.distanceM}, std::pair{"species", a.species}}) {
    auto in = OIIO::ImageInput::open(scene::aovPathFor(png, name).string());
    ASSERT_TRUE(in) << name;
    EXPECT_EQ(in->spec().width, 3);
    EXPECT_EQ(in->spec().height, 2);
    EXPECT_EQ(in->spec().nchannels, 1);
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::FLOAT);
    std::vector<float> got(6);
    ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, got.data()));
    EXPECT_EQ(got, values) << name;
  }
  // A directory in the way of one: an error naming it, and the other one not left behind.
  fs::remove(scene::aovPathFor(png, "depth"));
  fs::remove(scene::aovPathFor(png, "species"));
  fs::create_directories(scene::aovPathFor(png, "species"));
  auto failed = scene::writeFrameAovs(png, a, which);
  ASSERT_FALSE(failed.ok());
  EXPECT_NE(failed.error().message.find("still.species.tif"), std::string::npos) << failed.error().message;
  EXPECT_FALSE(fs::exists(scene::aovPathFor(png, "depth")));
}

}  // namespace
}  // namespace vegstream
