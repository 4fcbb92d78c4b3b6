#pragma once
// A camera in a local ENU frame (local_frame.h), in double precision, and its matrices: what the
// frame's stages turn a flight pose into once (scene/frame_context.h) and hand to the terrain's
// views and to the renderer alike. Plain maths on glm; the projection follows the renderer's
// conventions (Vulkan clip space, reverse-Z) so every folder builds the same matrices.

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace vegstream::geo {

struct Camera {
  glm::dvec3 position{0.0};
  glm::dvec3 forward{0.0, 1.0, 0.0};  // unit view direction
  glm::dvec3 up{0.0, 0.0, 1.0};       // approximate up; re-orthogonalised
  double verticalFovDeg = 55.0;
  double nearM = 1.0;
  double farM = 150'000.0;
};

// Rotation-only view matrix: the camera at the origin looking along forward (right-handed,
// looking down −z in view space).
glm::dmat4 viewRotation(const Camera& camera);
// Reverse-Z perspective for Vulkan clip space (y down, depth 1 at near, 0 at far).
glm::dmat4 projection(const Camera& camera, double aspect);
// Reverse-Z depth of a point at view distance d (along the view axis): n(f − d) / ((f − n) d).
double reverseZDepth(const Camera& camera, double viewDistance);

}  // namespace vegstream::geo
