#pragma once
// The trees' GPU data as plain data (issue 20): what scene/ hands the renderer (instances in pages,
// the models) and what it gets back (TreeFigures). No Vulkan here; shaders/common/tree_layout.glsl
// mirrors the GPU structs (std430 / std140) and the static_asserts keep the two in step.
//
// Trees live in a pool of pages of kTreePageSize instances on the GPU: scene/tree_field.h places
// the trees of a world tile once (vegetation/tree_placement.h), gives the tile pages and uploads
// them; only the per-page counts travel every frame. The classify pass (shaders/tree_classify.comp)
// then culls every slot, picks each tree's level of detail (full model, reduced model, octahedral
// impostor, nothing: the terrain's own colour) with dithered cross-fades between them, and appends
// it to the indirect draws of its model (render/tree_pass.h).

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "vegetation/tree_model.h"

namespace vegstream::render {

// One tree, 32 bytes (std430). Position in the dataset's local ENU frame, float: 2 mm at 20 km
// from the frame's origin, and trees are compared with a float camera position on the GPU.
struct TreeInstanceGpu {
  float position[3];  // root, m
  uint32_t model;     // index into the models given to Renderer::setTreeModels
  float heightM;      // this tree's height
  float crownM;       // its crown width
  uint32_t seed;      // Philox word: yaw, lean, branch angles, sway phases
  // The imagery's colour under the tree, sRGB-encoded bytes in r, g, b (the leaves take it:
  // shaders/common/tree_shading.glsl treeLeafAlbedo), and a colour factor in a (s′ of the species
  // choice: a minority tree is paler), as packUnorm4x8.
  uint32_t colour;
};
static_assert(sizeof(TreeInstanceGpu) == 32);

inline constexpr uint32_t kTreePageSize = 256;  // instances per page
inline constexpr uint32_t kMaxTreeModels = 32;  // models in all (species × variants)
inline constexpr uint32_t kTreeLods = 3;        // full, reduced, impostor

// Copies `count` instances into page `page` before the frame draws; `instances` must stay alive
// until submitFrame returns.
struct TreePageUpload {
  uint32_t page = 0;
  uint32_t count = 0;
  const TreeInstanceGpu* instances = nullptr;
};

// How far each level of detail reaches, in tree heights (so a tall tree keeps its model
// farther), for a 1080-line view of 55°: the renderer scales both by the view's pixels per radian
// (treeLodScale), so a tree switches at the same size on screen in any window — a 320 × 180 frame
// draws the full model only within a sixth of the distance. Trees end at `horizonM` (metres, not
// scaled). Each switch cross-fades over `fadeShare` of its distance.
//
// Each level's cost on the H200 is its pixels times its layers of cards (render/README.md
// "Trees on the H200"): at 1080 lines, the full model up to 1.6 heights (24 m for a 15 m tree),
// the reduced one up to 4 (60 m), where the impostor's 96-pixel views are about 0.4 as sharp as
// the screen.
struct TreeLodDistances {
  float fullHeights = 1.6f;     // full model up to 1.6 heights
  float reducedHeights = 4.0f;  // reduced model up to 4 heights, the impostor beyond
  // Impostors end (fading to the terrain's own colour) where a tree is about 5 pixels tall: 200
  // heights at 1080 lines (3 km for a 15 m tree, where the horizon ends them too), 33 in a
  // 180-line frame. Scaled like the two above.
  float impostorEndHeights = 200.0f;
  float horizonM = 3000.0f;  // impostors fade out to the terrain's own colour over the last fadeShare
  float fadeShare = 0.15f;
  // The near fade (metres, not scaled with the view: it is about the lens, not the pixels): the
  // models dissolve within nearFadeM of the camera and are gone within half of it, their crowns'
  // cores shrinking away (shaders/common/tree_layout.glsl treeNearKeep, tree.vert). Flying through
  // a crown then shows the trunks and the crowns beyond instead of a screen filled by the cards a
  // metre away. 0: off, the default: at 4 m it made kolob-forest's p99 at 1080p 2.7 ms slower on
  // an H100, the cores it takes away no longer hiding the cards behind them (bench/README.md).
  float nearFadeM = 0.0f;
};

// The factor the level-of-detail distances are scaled by for a view `heightPx` tall with a
// vertical field of view of `fovDeg`: its pixels per radian over a 1080-line, 55° view's.
inline float treeLodScale(double heightPx, double fovDeg) {
  const double reference = 540.0 / 0.52056705055174;  // tan(27.5°)
  return static_cast<float>(0.5 * heightPx / std::tan(0.5 * fovDeg * 3.14159265358979323846 / 180.0) / reference);
}

// The trees of one frame; null in FrameRequest: none drawn.
struct TreeRequest {
  std::span<const TreePageUpload> uploads;
  // Instances per page, for every page up to the highest in use (0: empty page). Must stay alive
  // until submitFrame returns.
  std::span<const uint32_t> pageCounts;
  TreeLodDistances lod;
  bool fades = true;    // false: hard switches (to show what the cross-fades hide)
  bool shadows = true;  // the trees cast into the cascaded sun shadow map
  bool cores = true;    // the crowns' opaque cores (vegetation/tree_core.h): false to compare without
  // Local ENU position of the camera (the instances' frame); the renderer's Camera is the same
  // point, this gives it to the trees in their frame.
  double cameraEnu[3] = {0.0, 0.0, 0.0};
  float timeS = 0.0f;  // simulation time, for the sway
};

// One species' models as the scene built them (vegetation/tree_model.h): `variants` models each.
struct TreeModelSet {
  uint32_t species = 0;  // catalog index
  vegetation::TreeParams params;
  std::vector<vegetation::TreeModel> variants;
};

// What the trees did in one frame, read back after its fence.
inline constexpr uint32_t kTreeShadowCascades = 3;  // render/shadow_cascades.h kShadowCascades

struct TreeFigures {
  uint32_t pages = 0;                            // pages classified
  uint32_t instances = 0;                        // trees in them
  uint32_t full = 0, reduced = 0, impostor = 0;  // appended per level (a tree cross-fading counts in two)
  uint32_t dropped = 0;                          // appended past a list's capacity (not drawn; shadow casters included)
  std::array<uint32_t, kTreeShadowCascades> shadowCasters{};  // trees cast into each sun cascade
  bool gpuCounts = false;                                     // the counts above were read back
};

}  // namespace vegstream::render
