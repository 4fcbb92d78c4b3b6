#pragma once
// The one triangle an impostor is drawn on (issue 17). On the H200 the trees' impostors are bound
// by the graphics units' primitive rate, not their fragments (measured: a hexagon of four
// triangles instead of the rectangle's two, 12–31 % fewer fragments, made the trees pass slower).
// So each impostor is a single triangle — apex above the crown, base on the bottom edge — chosen
// per model and elevation so that every vertex of the model stays inside it: the same
// silhouette from half the primitives. The fragment stage discards what falls outside the
// captured cell (the triangle may reach past it).
//
// The rectangle the model fills, seen at elevation E (sin E = the captured view's z), about the
// model's centre: half extents X = min(1.08 · crown radius, R), Y = min(0.55 · height · cos E +
// 1.08 · crown radius · sin E, R), R the impostor's half extent. A model vertex at height z, ρ
// from the axis, turned by any yaw φ, lands at x = ρ cos φ, y = (z − centre) cos E − ρ sin φ
// sin E. The triangle, in the rectangle's units (x as a share of X, up = 0 at its bottom edge … 1
// at its top): apex (0, a), base from (−b, 0) to (b, 0). Plain maths, no Vulkan.

#include <span>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "vegetation/tree_model.h"

namespace vegstream::render {

struct ImpostorQuadShape {
  float heightM = 0.0f;       // the model's height (TreeModelGpu::shape.x)
  float crownRadiusM = 0.0f;  // shape.y
  float halfExtentM = 0.0f;   // R, shape.z
  float centreZ = 0.0f;       // shape.w
};

// The rectangle's half extents (X, Y) for sin E: the vertex stage's formula.
glm::vec2 impostorQuadHalf(const ImpostorQuadShape& q, float sinE);

// Per quarter of sin E ([0, ¼), [¼, ½), [½, ¾), [¾, 1]; a vec4's component = the bin): the apex
// height a and the base's half width b of the least triangle that holds every vertex of
// `vertices` at every yaw and every elevation of the bin (a margin of 3 % of the width).
struct ImpostorTriangle {
  glm::vec4 apex{0.0f}, base{0.0f};
};
ImpostorTriangle impostorTriangle(std::span<const vegetation::TreeVertex> vertices, const ImpostorQuadShape& q);

// The triangle's half width (a share of X) in bin `bin` at `up`.
inline float impostorTriangleWidth(const ImpostorTriangle& t, int bin, float up) {
  return t.base[bin] * (t.apex[bin] - up) / t.apex[bin];
}

}  // namespace vegstream::render
