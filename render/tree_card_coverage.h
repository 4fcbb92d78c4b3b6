#pragma once
// The trees' leaf cards' coverage texture (issue 44: the trees pass's fragments). The outlines of
// shaders/common/tree_card_shape.glsl — the same source text, compiled here as C++ — baked once at
// start-up into an R8 array image that tree.frag samples (common/tree_coverage.glsl) instead of
// evaluating the outline per fragment: the H200 runs fragment stages on a few of its units, and
// the needles' two integer hashes and six smoothsteps were most of a card fragment's work.
//
// Layer 0 is a conifer card's needle spray, layer 1 a broadleaf card's clump of leaves, each
// kTreeCardSize² texels with kTreeCardLevels mip levels. A level's texel is the mean coverage over
// its square (a box filter, as the sampler's trilinear reads assume): level 0 from 2 × 2 points a
// texel, each finer-than-a-needle level from the four texels above it, and the levels whose texel
// spans a third of a needle row or more from 4 × 4 points of the outline at that level's needle
// detail (needleDetail: the needles give way to their mean coverage, as the fragment stage did
// from its footprint, so a distant crown keeps the coverage it has up close). Deterministic: the
// same bytes on every device.

#include <cstdint>
#include <vector>

#include "render/context.h"
#include "render/descriptors.h"
#include "render/gpu_resources.h"
#include "simulation/shared/glsl_compat.h"

namespace vegstream::render {

// glsl_compat.h defines VS_INLINE once; simulation/shared_code.h undefines it after its use.
#ifndef VS_INLINE
#define VS_INLINE inline
#define VEGSTREAM_TREE_CARD_DEFINED_VS
#endif
namespace card_shape {  // the shared GLSL, as C++
using namespace vegstream::simulation::shader;
#include "shaders/common/tree_card_shape.glsl"
}  // namespace card_shape
#ifdef VEGSTREAM_TREE_CARD_DEFINED_VS
#undef VS_INLINE
#undef VEGSTREAM_TREE_CARD_DEFINED_VS
#endif

// kTreeCardSize (level 0's side) and kTreeCardFinerLevels come from the shared file: a conifer
// card is read that many levels finer than the pixel's footprint (tree_coverage.glsl
// treeCardCoverage), so level L serves a footprint of 2^kTreeCardFinerLevels of its texels and its
// needles fade as the fragment stage faded them there.
using card_shape::kTreeCardFinerLevels;
using card_shape::kTreeCardSize;
inline constexpr uint32_t kTreeCardLevels = 7;  // 256 … 4 texels a side
inline constexpr uint32_t kTreeCardLayers = 2;  // 0 conifer, 1 broadleaf
static_assert((kTreeCardSize >> (kTreeCardLevels - 1)) >= 1);

// One layer's mip levels, coverage 0 … 1 (level L: (kTreeCardSize >> L)² values, row-major, v
// along the rows: texel (x, y) covers uv [x, x + 1] × [y, y + 1] / size).
std::vector<std::vector<float>> bakeTreeCardLayer(uint32_t layer);
// The outline itself at one point (shaders/common/tree_card_shape.glsl, layer 0 with the needles'
// `detail`): what the levels average.
float treeCardOutline(uint32_t layer, float u, float v, float detail);
// The needles' detail at level `level` (1: drawn, 0: their mean): needleDetail of the footprint
// the level serves.
float treeCardLevelDetail(uint32_t level);

// The baked texture on the GPU, shader-readable, with its trilinear clamp sampler.
class TreeCardCoverage {
 public:
  explicit TreeCardCoverage(const Context& ctx);  // waits for the upload
  VkImageView view() const { return image_.view.get(); }
  VkSampler sampler() const { return sampler_.get(); }
  uint64_t gpuBytes() const { return image_.bytes; }

 private:
  GpuImage image_;
  Sampler sampler_;
};

}  // namespace vegstream::render
