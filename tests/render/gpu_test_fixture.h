#pragma once
// Base for every test that touches the GPU: validation layers on, and the test fails on any
// validation message of warning or error severity (each message is printed).

#include <memory>

#include <gtest/gtest.h>

#include "render/context.h"
#include "render/renderer.h"
#include "terrain/terrain_mesh.h"

namespace vegstream::render::testing {

class GpuTest : public ::testing::Test {
 protected:
  std::shared_ptr<ValidationLog> validation = std::make_shared<ValidationLog>();

  RendererOptions options(uint32_t width, uint32_t height, int msaa) const {
    RendererOptions o;
    o.width = width;
    o.height = height;
    o.msaa = msaa;
    o.context.validate = true;
    o.context.validationLog = validation;
    return o;
  }

  std::unique_ptr<Renderer> makeRenderer(uint32_t width, uint32_t height, int msaa) {
    auto r = Renderer::create(options(width, height, msaa));
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return r.ok() ? std::move(*r) : nullptr;
  }

  // A bare context (no renderer) with the validation layers reporting to this test.
  std::unique_ptr<Context> validatedContext() {
    ContextOptions o;
    o.validate = true;
    o.validationLog = validation;
    auto created = Context::create(o);
    EXPECT_TRUE(created.ok()) << (created.ok() ? "" : created.error().message);
    return created.ok() ? std::move(*created) : nullptr;
  }

  void TearDown() override {
    for (const auto& m : validation->messages()) ADD_FAILURE() << "validation: " << m;
    EXPECT_EQ(validation->errors(), 0);
    EXPECT_EQ(validation->warnings(), 0);
  }
};

// A flat square of side `size` metres centred on the origin at height z, subdivided n × n,
// facing up (counter-clockwise seen from above).
inline terrain::TerrainMesh flatPlane(double size, int n, float z) {
  terrain::TerrainMesh mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = static_cast<float>(-0.5 * size + size * i / n);
      const float y = static_cast<float>(-0.5 * size + size * j / n);
      mesh.vertices.push_back({{x, y, z}, {0.0f, 0.0f, 1.0f}, 1500.0f});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto a = static_cast<uint32_t>(j * (n + 1) + i), b = a + 1;
      const auto c = static_cast<uint32_t>((j + 1) * (n + 1) + i), d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, c, b, d, c});
    }
  return mesh;
}

}  // namespace vegstream::render::testing
