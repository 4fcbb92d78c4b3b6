#pragma once
// A drawable terrain mesh: float vertices relative to a double-precision origin in the local
// ENU frame (the renderer adds origin − camera in double, then draws in float), 32-bit indices.
// Layout shared with shaders/terrain.vert (checked in render/terrain_pass.cpp).

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace vegstream::terrain {

struct TerrainVertex {
  glm::vec3 position;  // metres from TerrainMesh::origin, local ENU
  glm::vec3 normal;    // unit, local ENU
  float heightMsl;     // metres above mean sea level, for colouring
  glm::vec2 uv;        // imagery texture coordinates
};

struct TerrainMesh {
  glm::dvec3 origin{0.0};
  std::vector<TerrainVertex> vertices;
  std::vector<uint32_t> indices;  // triangle list, counter-clockwise seen from above

  size_t triangleCount() const { return indices.size() / 3; }
};

}  // namespace vegstream::terrain
