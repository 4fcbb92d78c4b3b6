// The area a tree model's crown covers seen from straight above (issue 41 item 6).
//
// A crown width in forestry is usually the diameter of the crown's projected area (the "crown
// projection area", CPA), and the tree placement spaces, thins and closes its crowns as disks of
// that width (tree_placement.h). A procedural crown's outline is ragged — a conifer's whorls of
// branches are a star from above — so its widest reach (TreeModel::crownRadiusM) encloses ground
// between the branches. The radius of the disk of the same area as the projection is the one to
// scale a model by when a tree asks for a crown width: then its crown covers the ground its disk
// stands for.
#pragma once

#include "vegetation/tree_model.h"

namespace vegstream::vegetation {

// The radius (m) of the disk whose area is that of `mesh`'s triangles projected straight down onto
// the ground (their union), sampled at the centres of a `cells` × `cells` grid over the mesh's
// horizontal bounds. Every triangle counts whole: bark, cards (as their quads; their texture's
// holes are finer than the gaps between branches) and the crown's core. 0 for an empty mesh.
// Deterministic. Contract (asserted): 16 ≤ cells ≤ 1024.
float crownProjectionRadius(const TreeMesh& mesh, int cells = 128);

}  // namespace vegstream::vegetation
