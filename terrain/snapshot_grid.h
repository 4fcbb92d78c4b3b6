#pragma once
// Bridges a loaded dataset snapshot (streaming/) to the terrain's plain grid and mesh: heights
// as a Web Mercator HeightGrid, and imagery texture coordinates for the mesh's vertices.

#include <functional>

#include <glm/vec2.hpp>

#include "streaming/dataset_snapshot.h"
#include "terrain/height_grid.h"

namespace vegstream::terrain {

HeightGrid heightGridFrom(const streaming::HeightMosaic& mosaic);

}  // namespace vegstream::terrain
