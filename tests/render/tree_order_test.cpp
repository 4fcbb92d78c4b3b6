// The trees' near lists are drawn nearest first (issue 41 item 7, shaders/tree_sort.comp): a
// grove uploaded far to near, seen from inside it on lavapipe with validation on. The classify's
// appends keep (about) the upload order; after the sort every model's full and reduced list runs
// by distance from the camera, holds each tree once, and holds what the classify counted.
#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include <glm/geometric.hpp>

#include "gpu_test_fixture.h"
#include "tests/support/plant_field_scene.h"
#include "tree_frame.h"
#include "vegetation/tree_model.h"

namespace vegstream::render::testing {
namespace {

constexpr float kTreeHeight = 12.0f, kCrown = 4.0f;

std::vector<TreeModelSet> broadleafModel() {
  TreeModelSet set;
  for (const vegetation::Species& s : vegetation::defaultSpeciesCatalog().species)
    if (vegetation::isTree(s) && s.tree.form == vegetation::TreeForm::Broadleaf) {
      set.params = s.tree;
      break;
    }
  set.variants.push_back(vegetation::buildTreeModel(set.params, kTreeHeight, kCrown, 3u));
  return {set};
}

class TreeOrderTest : public GpuTest {};

TEST_F(TreeOrderTest, NearListsAreDrawnNearestFirst) {
  auto r = makeRenderer(160, 90, 1);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setTreeModels(broadleafModel()).ok());
  // A 6 × 8 grove 6 m apart ahead of the camera, uploaded from the far row to the near one.
  std::vector<TreeInstanceGpu> trees;
  for (int row = 7; row >= 0; --row)
    for (int col = 0; col < 6; ++col) {
      TreeInstanceGpu t{};
      t.position[0] = float(col - 2.5) * 6.0f + 1.3f * float(row % 2);
      t.position[1] = 8.0f + float(row) * 6.0f;
      t.heightM = kTreeHeight;
      t.crownM = kCrown;
      t.seed = 0x9e3779b9u * uint32_t(row * 6 + col + 1);
      t.colour = 0xff000000u;
      trees.push_back(t);
    }
  terrain::TerrainMesh plane = flatPlane(200.0, 8, 0.0f);
  TerrainDraw draw{&plane};
  Camera cam;
  cam.position = {0.0, 0.0, 3.0};
  cam.forward = glm::normalize(glm::dvec3(0.0, 1.0, 0.05));
  cam.up = {0.0, 0.0, 1.0};
  cam.verticalFovDeg = 60.0;
  const FrameResult f = renderTreeFrame(*r, cam, {0.5, -0.5, 0.7}, draw, nullptr, trees, true, false);
  ASSERT_TRUE(f.trees);
  const auto list = r->readTreeList(0, 0);
  ASSERT_TRUE(list.ok()) << list.error().message;
  EXPECT_EQ(list->size(), f.trees->full) << "the list holds what the classify appended";
  EXPECT_GT(list->size(), 20u) << "most of the grove is in view";
  ASSERT_LE(list->size(), trees.size());
  std::set<uint32_t> seen;
  double last = 0.0;
  int inversions = 0;
  for (uint32_t i : *list) {
    ASSERT_LT(i, trees.size());
    EXPECT_TRUE(seen.insert(i).second) << "tree " << i << " listed twice";
    const glm::dvec3 p(trees[i].position[0], trees[i].position[1], trees[i].position[2]);
    const double d = glm::length(p - cam.position);
    if (d < last - 1e-3) ++inversions;
    last = d;
  }
  EXPECT_EQ(inversions, 0) << "the full models' list runs nearest first";
  const auto reduced = r->readTreeList(0, 1);
  ASSERT_TRUE(reduced.ok());
  EXPECT_EQ(reduced->size(), f.trees->reduced);
  EXPECT_FALSE(r->readTreeList(1, 0).ok()) << "one model only";
  EXPECT_FALSE(r->readTreeList(0, 2).ok()) << "impostors have no mesh list";
}

}  // namespace
}  // namespace vegstream::render::testing
