// ShadowRefresh (render/shadow_refresh.h): which cascades a frame draws again, and the matrices
// of those it keeps. Plain maths, no GPU.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "render/frame_types.h"
#include "render/shadow_cascades.h"
#include "render/shadow_refresh.h"

namespace vegstream::render {
namespace {

Camera cameraAt(const glm::dvec3& position) {
  Camera c;
  c.position = position;
  c.forward = glm::normalize(glm::dvec3(0.2, 1.0, -0.1));
  return c;
}

const glm::dvec3 kSun = glm::normalize(glm::dvec3(0.3, -0.4, 0.8));

// A flight at 20 m/s, 60 frames a second: one cascade a frame, the nearest every other frame, the
// two farther ones every fourth; and a kept layer maps every world point where the frame that
// drew it did.
TEST(ShadowRefresh, TheFarCascadesTakeTurnsAndAKeptLayerStaysPutInTheWorld) {
  ShadowRefresh refresh;
  ShadowSettings settings;
  std::array<int, kShadowCascades> drawn{};
  std::array<ShadowCascades, kShadowCascades> whenDrawn{};  // each cascade's last drawn matrices
  std::array<glm::dvec3, kShadowCascades> drawnFrom{};
  const glm::dvec3 world(150.0, 420.0, 12.0);  // a point in the second and third slices' boxes
  for (uint64_t frame = 0; frame < 120; ++frame) {
    const glm::dvec3 eye(0.0, 20.0 * double(frame) / 60.0, 30.0);
    ShadowCascades c = shadowCascades(cameraAt(eye), 16.0 / 9.0, kSun, settings);
    const ShadowCascades fresh = c;
    const uint32_t mask = refresh.plan(c, eye, kSun, frame);
    EXPECT_EQ(c.drawn, mask) << "what the classify casts into and the shadow pass draws";
    if (frame == 0) EXPECT_EQ(mask, 7u) << "the first frame draws every cascade";
    else EXPECT_EQ(mask, frame % 2 == 0 ? 1u : frame % 4 == 1 ? 2u : 4u) << "frame " << frame;
    for (int k = 0; k < kShadowCascades; ++k) {
      const auto i = size_t(k);
      if (mask & (1u << k)) {
        ++drawn[i];
        EXPECT_EQ(c.matrices[i], fresh.matrices[i]) << "a cascade drawn this frame has this frame's matrix";
        whenDrawn[i] = fresh;
        drawnFrom[i] = eye;
        continue;
      }
      // Kept: this frame's camera-relative position of the point, through the kept matrix, lands
      // where the drawing frame put it.
      const glm::vec4 now = c.matrices[i] * glm::vec4(glm::vec3(world - eye), 1.0f);
      const glm::vec4 then = whenDrawn[i].matrices[i] * glm::vec4(glm::vec3(world - drawnFrom[i]), 1.0f);
      EXPECT_LT(glm::length(glm::vec3(now - then)), 1e-5f) << "frame " << frame << " cascade " << k;
    }
  }
  EXPECT_EQ(drawn[0], 60);  // the first frame draws all three
  EXPECT_EQ(drawn[1], 31);
  EXPECT_EQ(drawn[2], 31);
}

TEST(ShadowRefresh, EveryCascadeIsDrawnAfterAResetATurnOfTheSunOrAJump) {
  ShadowRefresh refresh;
  ShadowSettings settings;
  const glm::dvec3 eye(0.0, 0.0, 30.0);
  auto plan = [&](const glm::dvec3& at, const glm::dvec3& sun, uint64_t frame) {
    ShadowCascades c = shadowCascades(cameraAt(at), 16.0 / 9.0, sun, settings);
    return refresh.plan(c, at, sun, frame);
  };
  EXPECT_EQ(plan(eye, kSun, 0), 7u);
  EXPECT_EQ(plan(eye, kSun, 1), 2u);
  refresh.reset();  // a frame without shadows
  EXPECT_EQ(plan(eye, kSun, 2), 7u);
  EXPECT_EQ(plan(eye, kSun, 3), 4u);
  const glm::dvec3 later = glm::normalize(kSun + glm::dvec3(0.0, 0.0, 0.01));
  EXPECT_EQ(plan(eye, later, 4), 7u) << "the sun turned";
  EXPECT_EQ(plan(eye, later, 5), 2u);
  EXPECT_EQ(plan(eye + glm::dvec3(0.0, 40.0, 0.0), later, 6), 7u) << "a jump of 40 m: more than 600 m / 20";
  EXPECT_EQ(plan(eye + glm::dvec3(0.0, 43.0, 0.0), later, 7), 1u | 4u)
      << "its turn for the farthest; the nearest moved 3 m, over 40 m / 20; the middle one waits";
  EXPECT_EQ(plan(eye + glm::dvec3(0.0, 44.0, 0.0), later, 9), 2u) << "1 m in two frames: the nearest waits its turn";
}

}  // namespace
}  // namespace vegstream::render
