#pragma once
// A drawable terrain mesh: float vertices relative to a double-precision origin in the local
// ENU frame (the renderer adds origin − camera in double, then draws in float), 32-bit indices.
// Layout shared with shaders/terrain.vert (checked in render/terrain_pass.cpp).
//
// A mesh is its own triangles plus references to chunks: blocks of triangles the producer keeps
// across frames (ROAM's drawn chunks, roam_chunks.h) with the same origin and imagery. A chunk
// is never copied into the mesh: it keeps an id for as long as its triangles stay the same, and
// a version that changes when its vertices move, so a consumer that keeps chunks (the renderer,
// on the GPU) touches only the ones that changed. A chunk is drawn whole (ROAM's straddling
// chunks too, roam_chunks.h).

#include <cstdint>
#include <limits>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace vegstream::terrain {

struct TerrainVertex {
  glm::vec3 position;  // metres from TerrainMesh::origin, local ENU
  glm::vec3 normal;    // unit, local ENU
  float heightMsl;     // metres above mean sea level, for colouring
  glm::vec2 uv;        // imagery texture coordinates
};

// Kept by its producer between frames; valid until the producer's next frame.
struct TerrainChunk {
  uint64_t id = 0;       // new whenever its triangles change (never reused in a process)
  uint64_t version = 0;  // changes whenever its vertices move (the same triangles)
  std::vector<TerrainVertex> vertices;
  std::vector<uint32_t> indices;  // into vertices
  // The box of its vertices' positions (meaningless without vertices), kept by the producer
  // whenever they change (keepBounds), so a consumer that orders or culls the chunks every frame
  // reads two corners instead of every vertex.
  glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};
};

// Grows the box [lo, hi] by the positions of `vertices`.
inline void growBox(const std::vector<TerrainVertex>& vertices, glm::vec3& lo, glm::vec3& hi) {
  for (const TerrainVertex& v : vertices) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
}

// Sets c.boundsMin / boundsMax to the box of c.vertices.
inline void keepBounds(TerrainChunk& c) {
  c.boundsMin = glm::vec3(std::numeric_limits<float>::max());
  c.boundsMax = glm::vec3(std::numeric_limits<float>::lowest());
  growBox(c.vertices, c.boundsMin, c.boundsMax);
}

struct TerrainChunkDraw {
  const TerrainChunk* chunk = nullptr;
  // A copy of the chunk's header as it is drawn this frame, so that a consumer that only places
  // or orders the chunks (the renderer's frame thread) reads this list and not the chunks' own
  // records, a cache miss a chunk; `count` is all of chunk->indices (a chunk is drawn whole).
  uint64_t id = 0, version = 0;
  uint32_t vertexCount = 0, count = 0;
  glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};

  static TerrainChunkDraw of(const TerrainChunk& c) {
    return {&c,
            c.id,
            c.version,
            static_cast<uint32_t>(c.vertices.size()),
            static_cast<uint32_t>(c.indices.size()),
            c.boundsMin,
            c.boundsMax};
  }
};

struct TerrainMesh {
  glm::dvec3 origin{0.0};
  std::vector<TerrainVertex> vertices;
  std::vector<uint32_t> indices;  // triangle list, counter-clockwise seen from above
  std::vector<TerrainChunkDraw> chunks;

  size_t triangleCount() const {
    size_t n = indices.size();
    for (const TerrainChunkDraw& c : chunks) n += c.count;
    return n / 3;
  }
  bool empty() const { return indices.empty() && chunks.empty(); }
  void clear() {
    vertices.clear();
    indices.clear();
    chunks.clear();
  }
};

// Calls f(a, b, c) with the vertices of every triangle of `m`: its own, then its chunks'.
template <class F>
void forEachTriangle(const TerrainMesh& m, F&& f) {
  for (size_t i = 0; i + 2 < m.indices.size(); i += 3)
    f(m.vertices[m.indices[i]], m.vertices[m.indices[i + 1]], m.vertices[m.indices[i + 2]]);
  for (const TerrainChunkDraw& d : m.chunks) {
    const uint32_t* idx = d.chunk->indices.data();
    const std::vector<TerrainVertex>& v = d.chunk->vertices;
    for (uint32_t i = 0; i + 2 < d.count; i += 3) f(v[idx[i]], v[idx[i + 1]], v[idx[i + 2]]);
  }
}

}  // namespace vegstream::terrain
