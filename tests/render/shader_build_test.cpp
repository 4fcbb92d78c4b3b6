// The shader build: every GLSL file became SPIR-V at build time (magic number, version), and
// the driver accepts each module with the validation layers watching (they run spirv-val).

#include <cstdint>
#include <span>

#include "gpu_test_fixture.h"
#include "render/context.h"
#include "render/pipeline_builder.h"
#include "shaders/colour_score_check.comp.h"
#include "shaders/sky.frag.h"
#include "shaders/sky.vert.h"
#include "shaders/terrain.frag.h"
#include "shaders/terrain.vert.h"

namespace vegstream::render::testing {
namespace {

const std::span<const uint32_t> kModules[] = {spv_sky_vert, spv_sky_frag, spv_terrain_vert, spv_terrain_frag,
                                              spv_colour_score_check_comp};

TEST(ShaderBuild, EveryShaderIsSpirv) {
  for (auto m : kModules) {
    ASSERT_GT(m.size(), 5u);
    EXPECT_EQ(m[0], 0x07230203u);  // SPIR-V magic
    EXPECT_GE(m[1], 0x00010000u);  // version 1.x
    EXPECT_GT(m[3], 1u);           // id bound: real code, not an empty module
  }
}

class ShaderModules : public GpuTest {};

TEST_F(ShaderModules, DriverAcceptsEveryModule) {
  ContextOptions o;
  o.validate = true;
  o.validationLog = validation;
  auto ctx = Context::create(o);
  ASSERT_TRUE(ctx.ok()) << ctx.error().message;
  for (auto m : kModules) {
    ShaderModule module = createShaderModule(**ctx, m, "test module");
    EXPECT_TRUE(static_cast<bool>(module));
  }
}

}  // namespace
}  // namespace vegstream::render::testing
