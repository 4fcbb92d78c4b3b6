// shaders/common/philox.glsl against vegetation/philox.h (Philox-2×32, core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2): shaders/philox_check.comp hashes 10⁶
// counter/key inputs made from the index with 3, 7 and 10 rounds; every word must equal the
// C++ bit for bit (plant placement is the same on CPU and GPU only if they do).

#include <cstdio>
#include <cstring>
#include <vector>

#include "compute_check.h"
#include "gpu_test_fixture.h"
#include "render/context.h"
#include "render/descriptors.h"
#include "render/gpu_resources.h"
#include "render/pipeline_builder.h"
#include "render/vk_check.h"
#include "shaders/philox_check.comp.h"
#include "vegetation/philox.h"

namespace vegstream::render::testing {
namespace {

namespace veg = vegstream::vegetation;

class PhiloxGpu : public GpuTest {};

TEST_F(PhiloxGpu, ShaderMatchesTheCppBitForBit) {
  const std::unique_ptr<Context> context = validatedContext();
  ASSERT_TRUE(context);
  const Context& ctx = *context;

  constexpr uint32_t count = 1000000;
  const VkDeviceSize outBytes = sizeof(uint32_t) * 6 * count;
  GpuBuffer outputs =
      createBuffer(ctx, outBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostReadback, "philox check outputs");
  const CheckBinding bindings[] = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, outputs.get()}};
  runComputeCheck(ctx, spv_philox_check_comp, bindings, std::as_bytes(std::span(&count, 1)), count, "philox check");
  std::vector<uint32_t> gpu(6 * size_t{count});
  std::memcpy(gpu.data(), outputs.mapped, outBytes);

  size_t mismatches[3] = {};
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t c0 = i, c1 = (i * 0x85EBCA6Bu) ^ 0xC2B2AE35u, key = i * 0x27D4EB2Fu + 0x165667B1u;
    const veg::Philox2x32Out cpu[3] = {veg::philox(c0, c1, key), veg::philox2x32<7>(c0, c1, key),
                                       veg::philox2x32<10>(c0, c1, key)};
    const uint32_t* g = &gpu[6 * size_t{i}];
    for (int r = 0; r < 3; ++r) {
      const bool same = g[2 * r] == cpu[r].x && g[2 * r + 1] == cpu[r].y;
      if (!same && mismatches[r] < 3)
        ADD_FAILURE() << "index " << i << " variant " << r << ": GPU " << g[2 * r] << " " << g[2 * r + 1] << ", CPU "
                      << cpu[r].x << " " << cpu[r].y;
      mismatches[r] += same ? 0 : 1;
    }
  }
  EXPECT_EQ(mismatches[0], 0u) << "Philox-2x32-3";
  EXPECT_EQ(mismatches[1], 0u) << "Philox-2x32-7";
  EXPECT_EQ(mismatches[2], 0u) << "Philox-2x32-10";
  // philoxU01 is exact by construction (24 bits in a float); the C++ u01 of the same word.
  static_assert(veg::u01(0xffffffffu) < 1.0f);
  std::printf("philox CPU vs GPU over %u inputs x 3 round counts: %zu, %zu, %zu mismatching\n", count, mismatches[0],
              mismatches[1], mismatches[2]);
}

}  // namespace
}  // namespace vegstream::render::testing
