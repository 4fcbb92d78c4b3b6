// shaders/common/colour_score.glsl + terrain_detail.glsl against vegetation/colour_score.h +
// terrain_types.h: a compute kernel (shaders/colour_score_check.comp) evaluates HSV, a score and
// the blend weights of the default terrain-type table — packed into the same uniform block the
// terrain pass uses — for a few hundred colours; they must agree with the C++ within 1e-4.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include <glm/vec4.hpp>

#include "compute_check.h"
#include "gpu_test_fixture.h"
#include "render/context.h"
#include "render/descriptors.h"
#include "render/gpu_resources.h"
#include "render/pipeline_builder.h"
#include "render/terrain_detail.h"
#include "render/vk_check.h"
#include "shaders/colour_score_check.comp.h"
#include "vegetation/colour_calibration.h"
#include "vegetation/terrain_types.h"

namespace vegstream::render::testing {
namespace {

namespace veg = vegstream::vegetation;

// Linear colours to check: a 6³ grid (primaries, greys, black, white included), the sRGB
// decodings of typical imagery colours, and each reference colour itself (the clamped,
// exact-match case).
std::vector<glm::vec4> testColours() {
  std::vector<glm::vec4> out;
  const float levels[] = {0.0f, 0.02f, 0.1f, 0.3f, 0.6f, 1.0f};
  for (float r : levels)
    for (float g : levels)
      for (float b : levels) out.emplace_back(r, g, b, 0.0f);
  auto fromSrgb = [](glm::vec3 c) {
    return glm::vec4(veg::srgbDecode(c.r), veg::srgbDecode(c.g), veg::srgbDecode(c.b), 0.0f);
  };
  const glm::vec3 typical[] = {{104, 120, 60},  {36, 42, 25},    {149, 101, 88},  {106, 86, 77}, {100, 88, 88},
                               {208, 196, 176}, {128, 128, 130}, {214, 188, 138}, {76, 91, 50}};
  for (glm::vec3 c : typical) out.push_back(fromSrgb(c / 255.0f));
  for (const veg::TerrainType& t : veg::defaultTerrainTypes())
    out.push_back(fromSrgb(veg::srgbFromHsv(t.score.reference)));
  return out;
}

class ColourScoreGpu : public GpuTest {};

TEST_F(ColourScoreGpu, ShaderMatchesTheCppWithin1e4) {
  const std::unique_ptr<Context> context = validatedContext();
  ASSERT_TRUE(context);
  const Context& ctx = *context;

  const std::vector<glm::vec4> colours = testColours();
  const auto count = static_cast<uint32_t>(colours.size());
  const TerrainDetailUniforms block = packTerrainDetail(veg::defaultTerrainTypes());
  GpuBuffer uniforms =
      createBuffer(ctx, sizeof(block), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUse::HostUpload, "check uniforms");
  std::memcpy(uniforms.mapped, &block, sizeof(block));
  GpuBuffer inputs = createBuffer(ctx, sizeof(glm::vec4) * count, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  MemoryUse::HostUpload, "check inputs");
  std::memcpy(inputs.mapped, colours.data(), sizeof(glm::vec4) * count);
  const VkDeviceSize outBytes = sizeof(glm::vec4) * 8 * count;
  // A calibration that is not the identity (a blue cast taken out, chroma raised) and an ExG term.
  veg::ColourCalibration calibration;
  calibration.rows = {glm::vec4(1.4f, 0.08f, -0.05f, -0.01f), glm::vec4(-0.02f, 1.2f, 0.04f, 0.005f),
                      glm::vec4(-0.1f, 0.15f, 0.7f, 0.02f)};
  struct CalibrationBlock {
    std::array<glm::vec4, 3> rows;
    glm::vec4 exg;
  } calib{calibration.rows, glm::vec4(0.3f, 1.5f, 0.0f, 0.0f)};
  GpuBuffer calibUniform =
      createBuffer(ctx, sizeof(calib), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUse::HostUpload, "check calibration");
  std::memcpy(calibUniform.mapped, &calib, sizeof(calib));
  GpuBuffer outputs =
      createBuffer(ctx, outBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostReadback, "check outputs");

  const CheckBinding bindings[] = {{1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniforms.get(), sizeof(block)},
                                   {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, inputs.get()},
                                   {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, outputs.get()},
                                   {4, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, calibUniform.get(), sizeof(calib)}};
  runComputeCheck(ctx, spv_colour_score_check_comp, bindings, std::as_bytes(std::span(&count, 1)), count,
                  "colour score check");
  std::vector<glm::vec4> gpu(8 * count);
  std::memcpy(gpu.data(), outputs.mapped, outBytes);

  const auto types = veg::defaultTerrainTypes();
  const auto params = veg::scoreParams(types);
  float worstHsv = 0.0f, worstWeight = 0.0f, worstLog = 0.0f, worstCal = 0.0f;
  for (uint32_t i = 0; i < count; ++i) {
    const glm::vec3 hsv = veg::hsvFromLinear(glm::vec3(colours[i]));
    const glm::vec4* g = &gpu[8 * size_t{i}];
    // The calibrated ground colour and its ExG, and a score with the ExG term.
    const veg::GroundColour cal = veg::calibratedGround(calibration, glm::vec3(colours[i]));
    worstCal = std::max({worstCal, veg::hueDistance(cal.hsv.x, g[6].x), std::abs(cal.hsv.y - g[6].y),
                         std::abs(cal.hsv.z - g[6].z), std::abs(cal.exg - g[6].w)});
    veg::ColourScoreParams withExg = params[0];
    withExg.ndviWeight = 0.0f;
    withExg.exgReference = calib.exg.x;
    withExg.exgWeight = calib.exg.y;
    const float logExg = veg::logColourScore(withExg, cal.hsv, veg::kNoNdvi, cal.exg);
    worstLog = std::max(worstLog, std::abs(logExg - g[7].x) / std::max(1.0f, std::abs(logExg)));
    worstHsv =
        std::max({worstHsv, veg::hueDistance(hsv.x, g[0].x), std::abs(hsv.y - g[0].y), std::abs(hsv.z - g[0].z)});
    // The score of type 0 (as a logarithm: it spans many orders of magnitude), relative.
    const float log0 = veg::logColourScore(params[0], hsv);
    worstLog = std::max(worstLog, std::abs(log0 - g[0].w) / std::max(1.0f, std::abs(log0)));
    const std::vector<float> w = veg::terrainTypeWeights(types, hsv);
    for (size_t t = 0; t < veg::kMaxTerrainTypes; ++t) {
      const float cpu = t < w.size() ? w[t] : 0.0f;
      const float got = g[1 + t / 4][static_cast<int>(t % 4)];
      worstWeight = std::max(worstWeight, std::abs(cpu - got));
      EXPECT_NEAR(cpu, got, 1e-4f) << "colour " << i << " type " << t;
    }
    const std::vector<float> s = veg::surfaceWeights(types, hsv);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(s[static_cast<size_t>(k)], g[5][k], 1e-4f) << "colour " << i;
  }
  EXPECT_LT(worstHsv, 1e-4f);
  EXPECT_LT(worstLog, 1e-4f);
  EXPECT_LT(worstCal, 1e-4f);
  std::printf("colour score CPU vs GPU over %u colours: HSV %.2g, log score %.2g (relative), weights %.2g, "
              "calibrated HSV + ExG %.2g\n",
              count, double(worstHsv), double(worstLog), double(worstWeight), double(worstCal));
}

}  // namespace
}  // namespace vegstream::render::testing
