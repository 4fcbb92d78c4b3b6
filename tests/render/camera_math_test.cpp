// Camera maths: rotation-only view, reverse-Z projection for Vulkan clip space.

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include "render/deletion_queue.h"
#include "render/frame_types.h"

namespace vegstream::render {
namespace {

glm::dvec3 ndc(const glm::dmat4& m, const glm::dvec3& p) {
  const glm::dvec4 c = m * glm::dvec4(p, 1.0);
  return glm::dvec3(c) / c.w;
}

TEST(CameraMath, ViewRotationMapsForwardToMinusZ) {
  Camera cam;
  cam.forward = glm::normalize(glm::dvec3(1, 1, -0.2));
  const glm::dvec4 v = viewRotation(cam) * glm::dvec4(cam.forward, 0.0);
  EXPECT_NEAR(v.x, 0.0, 1e-12);
  EXPECT_NEAR(v.y, 0.0, 1e-12);
  EXPECT_NEAR(v.z, -1.0, 1e-12);
}

TEST(CameraMath, ReverseZProjection) {
  Camera cam;
  cam.nearM = 0.5;
  cam.farM = 50'000.0;
  const glm::dmat4 p = projection(cam, 16.0 / 9.0);
  EXPECT_NEAR(ndc(p, {0, 0, -cam.nearM}).z, 1.0, 1e-12);
  EXPECT_NEAR(ndc(p, {0, 0, -cam.farM}).z, 0.0, 1e-9);
  for (double d : {1.0, 10.0, 1234.5, 40'000.0}) EXPECT_NEAR(ndc(p, {0, 0, -d}).z, reverseZDepth(cam, d), 1e-12);
  // Vulkan clip space: a point above the view axis lands in the upper half, i.e. negative y.
  EXPECT_LT(ndc(p, {0, 1, -10}).y, 0.0);
  // The top edge of the field of view maps to y = −1.
  const double t = std::tan(glm::radians(cam.verticalFovDeg) / 2.0);
  EXPECT_NEAR(ndc(p, {0, 10 * t, -10}).y, -1.0, 1e-12);
}

TEST(DeletionQueue, DestroysOnlyWhatCompletedFramesUsed) {
  DeletionQueue q;
  int destroyed = 0;
  struct Probe {
    int* counter;
    bool live = true;
    explicit Probe(int* c) : counter(c) {}
    Probe(Probe&& o) noexcept : counter(o.counter) { o.live = false; }
    ~Probe() {
      if (live) ++*counter;
    }
  };
  q.defer(3, Probe(&destroyed));
  q.defer(5, Probe(&destroyed));
  q.collect(2);
  EXPECT_EQ(destroyed, 0);
  q.collect(4);
  EXPECT_EQ(destroyed, 1);
  EXPECT_EQ(q.size(), 1u);
  q.collectAll();
  EXPECT_EQ(destroyed, 2);
}

}  // namespace
}  // namespace vegstream::render
