#pragma once
// One tree on a flat, evenly coloured plane (tree_shadow_test.cpp, tree_near_fade_test.cpp): the
// default catalog's first conifer as the renderer's one model, standing at the origin, drawn by
// renderTreeFrame (tree_frame.h).

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/plant_field_scene.h"
#include "tree_frame.h"
#include "vegetation/species_catalog.h"
#include "vegetation/tree_model.h"

namespace vegstream::render::testing {

// The default catalog's first tree species of `form`, one variant of heightM × crownM (variant
// seed 7).
inline TreeModelSet firstTreeOfForm(vegetation::TreeForm form, float heightM, float crownM) {
  TreeModelSet set;
  set.species = 0;
  for (const vegetation::Species& s : vegetation::defaultSpeciesCatalog().species)
    if (vegetation::isTree(s) && s.tree.form == form) {
      set.params = s.tree;
      break;
    }
  EXPECT_EQ(set.params.form, form);
  set.variants.push_back(vegetation::buildTreeModel(set.params, heightM, crownM, 7u));
  return set;
}

inline TreeModelSet loneConifer(float heightM, float crownM) {
  return firstTreeOfForm(vegetation::TreeForm::Conifer, heightM, crownM);
}

// The plane (kField wide, one imagery tile of one colour) and the tree on it, of instance seed
// `seed` (0: no yaw, no lean).
struct LoneTree {
  std::vector<uint8_t> tile = flatTile(150, 140, 120);
  terrain::TerrainMesh plane = flatPlane(kField, 8, 0.0f);
  TerrainDraw draw{&plane};
  ImageryUpload upload{0, tile};
  std::vector<TreeInstanceGpu> trees;

  LoneTree(float heightM, float crownM, uint32_t seed) {
    for (auto& v : plane.vertices) v.uv = fieldUv(v.position.x, v.position.y);
    draw.imageryLayer = 0;
    TreeInstanceGpu t{};
    t.heightM = heightM;
    t.crownM = crownM;
    t.seed = seed;
    t.colour = 0xff000000u;  // no imagery under it: the species' own leaves, full colour
    trees = {t};
  }

  // upload0: upload the plane's tile first (the renderer's first frame needs it).
  FrameResult render(Renderer& r, const Camera& cam, const glm::dvec3& sun, bool withTree, bool shadows, bool upload0,
                     float nearFadeM = TreeLodDistances{}.nearFadeM) {
    return renderTreeFrame(r, cam, sun, draw, upload0 ? &upload : nullptr, trees, withTree, shadows, nearFadeM);
  }
};

}  // namespace vegstream::render::testing
