#pragma once
// Base for every test that touches the GPU: validation layers on, and the test fails on any
// validation message of warning or error severity (each message is printed).

#include <cstdlib>
#include <memory>

#include <gtest/gtest.h>

#include "render/context.h"
#include "render/renderer.h"
#include "tests/support/plant_field_scene.h"
#include "terrain/terrain_mesh.h"

namespace vegstream::render::testing {

class GpuTest : public ::testing::Test {
 protected:
  std::shared_ptr<ValidationLog> validation = std::make_shared<ValidationLog>();

  RendererOptions options(uint32_t width, uint32_t height, int msaa,
                          TerrainShading shading = TerrainShading::Auto) const {
    RendererOptions o;
    o.width = width;
    o.height = height;
    o.msaa = msaa;
    o.terrainShading = shading;
    o.context.validate = true;
    o.context.validationLog = validation;
    return o;
  }

  std::unique_ptr<Renderer> makeRenderer(uint32_t width, uint32_t height, int msaa,
                                         TerrainShading shading = TerrainShading::Auto) {
    auto r = Renderer::create(options(width, height, msaa, shading));
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    if (!r.ok()) return nullptr;
    // The pipeline tests count and look at every kind's shadows; the shipped grass casts none
    // (config/species.json "shadows": dense blades cover them).
    EXPECT_TRUE((*r)->setSpeciesCatalog(shadowsEverywhere()).ok());
    return std::move(*r);
  }

  static vegetation::SpeciesCatalog shadowsEverywhere() {
    vegetation::SpeciesCatalog c = vegetation::defaultSpeciesCatalog();
    for (vegetation::Species& s : c.species) s.shadows = true;
    return c;
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

// Pixels of two same-sized images whose colour differs by more than `threshold` (of 255) in
// some channel (alpha ignored).
inline size_t pixelsOffBy(const ColorImage& a, const ColorImage& b, int threshold) {
  size_t n = 0;
  for (size_t i = 0; i + 3 < a.rgba.size() && i + 3 < b.rgba.size(); i += 4)
    for (size_t c = 0; c < 3; ++c)
      if (std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c])) > threshold) {
        ++n;
        break;
      }
  return n;
}

}  // namespace vegstream::render::testing
