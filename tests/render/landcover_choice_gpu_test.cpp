// shaders/common/species_choice.glsl's chooseSpeciesAllowed against vegetation/species_choice.h
// (issue 41, item 2: the species choice of core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt
// §3.3 eq. 16–18 restricted to the species the landcover class under a plant allows): a compute
// kernel (shaders/species_choice_check.comp) chooses, from the default catalog packed as the
// classify pass packs it, for a few thousand (colour, NDVI, z, landcover kind) inputs; species
// must be the same and s′ agree within 1e-5, with the validation layers silent.

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include <glm/vec4.hpp>

#include "compute_check.h"
#include "gpu_test_fixture.h"
#include "render/classify_layout.h"
#include "shaders/species_choice_check.comp.h"
#include "vegetation/landcover_species.h"
#include "vegetation/philox.h"
#include "vegetation/species_choice.h"

namespace vegstream::render::testing {
namespace {

namespace veg = vegstream::vegetation;

struct ChoiceInput {
  glm::vec4 hsvNdvi;
  glm::uvec4 zAllowed;
};
static_assert(sizeof(ChoiceInput) == 32);

class LandcoverChoiceGpu : public GpuTest {};

TEST_F(LandcoverChoiceGpu, ShaderChoosesAsTheCppWithinEachClass) {
  const std::unique_ptr<Context> context = validatedContext();
  ASSERT_TRUE(context);
  const Context& ctx = *context;
  const veg::SpeciesCatalog& catalog = veg::defaultSpeciesCatalog();

  // Every kind's mask, and every species (no landcover), over the same colours.
  std::vector<veg::SpeciesMask> masks{veg::kAllSpecies};
  for (size_t k = 0; k < kLandcoverKindCount; ++k)
    masks.push_back(veg::allowedSpecies(catalog, static_cast<LandcoverKind>(k)));
  std::vector<ChoiceInput> inputs;
  for (uint32_t i = 0; i < 400; ++i) {
    const veg::Philox2x32Out a = veg::philox(i, 1u, 0x1cu), b = veg::philox(i, 2u, 0x1cu);
    const glm::vec3 hsv(veg::u01(a.x), veg::u01(a.y), 0.6f * veg::u01(b.x));
    const float ndvi = (i % 3 == 0) ? veg::kNoNdvi : 2.0f * veg::u01(b.y) - 1.0f;
    for (veg::SpeciesMask m : masks) {
      float z = veg::u01(veg::philox(i, m, 0x2du).x);
      uint32_t zBits = 0;
      std::memcpy(&zBits, &z, 4);
      inputs.push_back({glm::vec4(hsv, ndvi), glm::uvec4(zBits, m, 0u, 0u)});
    }
  }
  const auto count = static_cast<uint32_t>(inputs.size());
  const SpeciesBlock block = packSpecies(catalog);
  GpuBuffer uniforms =
      createBuffer(ctx, sizeof(block), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUse::HostUpload, "check uniforms");
  std::memcpy(uniforms.mapped, &block, sizeof(block));
  GpuBuffer in = createBuffer(ctx, sizeof(ChoiceInput) * count, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              MemoryUse::HostUpload, "check inputs");
  std::memcpy(in.mapped, inputs.data(), sizeof(ChoiceInput) * count);
  const VkDeviceSize outBytes = sizeof(glm::vec2) * count;
  GpuBuffer out = createBuffer(ctx, outBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostReadback, "check out");
  const CheckBinding bindings[] = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniforms.get(), sizeof(block)},
                                   {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, in.get()},
                                   {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, out.get()}};
  runComputeCheck(ctx, spv_species_choice_check_comp, bindings, std::as_bytes(std::span(&count, 1)), count,
                  "species choice check");
  std::vector<glm::vec2> gpu(count);
  std::memcpy(gpu.data(), out.mapped, outBytes);

  uint32_t compared = 0, nearTie = 0, grown = 0, outsideMask = 0;
  for (uint32_t i = 0; i < count; ++i) {
    const ChoiceInput& c = inputs[i];
    float z = 0.0f;
    std::memcpy(&z, &c.zAllowed.x, 4);
    veg::SpeciesChoice cpu = veg::chooseSpecies(catalog, glm::vec3(c.hsvNdvi), z, c.hsvNdvi.w, veg::kNoExg, c.zAllowed.y);
    // The classify pass packs trees as bare (they grow on their own grid): the plants see −1.
    if (cpu.species >= 0 && veg::isTree(catalog.species[size_t(cpu.species)])) cpu.species = -1;
    if (std::abs(z - cpu.secondRatio) < 1e-4f) {  // z on the knife edge of eq. 18: float exp may differ
      ++nearTie;
      continue;
    }
    ++compared;
    EXPECT_EQ(cpu.species, static_cast<int>(gpu[i].x)) << "input " << i << " mask " << c.zAllowed.y;
    if (cpu.species >= 0) {
      ++grown;
      EXPECT_NEAR(cpu.sPrime, gpu[i].y, 1e-5f) << "input " << i;
      outsideMask += ((c.zAllowed.y >> uint32_t(gpu[i].x)) & 1u) == 0u;
    }
  }
  EXPECT_EQ(outsideMask, 0u);
  EXPECT_GT(grown, count / 5);
  EXPECT_LT(nearTie, count / 100);
  std::printf("landcover species choice CPU vs GPU: %u inputs compared (%u grow a plant), %u on eq. 18's edge\n",
              compared, grown, nearTie);
}

}  // namespace
}  // namespace vegstream::render::testing
