// seedTrianglesForGpu (scene.h): the frame's seed triangles as the classify pass reads them.
#include "scene/scene.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "terrain/seed_triangles.h"

namespace vegstream::scene {

void seedTrianglesForGpu(std::span<const terrain::SeedTriangle> seeds, const glm::dvec3& camera,
                         std::vector<render::SeedTriangleGpu>& out) {
  out.clear();
  out.reserve(seeds.size());
  for (const terrain::SeedTriangle& s : seeds) {
    if (s.imageryLayer < 0) continue;  // no imagery drawn under it yet: no colour, no species
    render::SeedTriangleGpu g;
    // Camera-relative in double, then float: centimetres stay exact kilometres from the origin.
    g.v0 = glm::vec4(glm::vec3(s.world[0] - camera), s.plantCount);
    g.v1 = glm::vec4(glm::vec3(s.world[1] - camera), 0.0f);
    g.v2 = glm::vec4(glm::vec3(s.world[2] - camera), 0.0f);
    g.uv01 = glm::vec4(s.imageryUv[0], s.imageryUv[1]);
    g.uv2 = s.imageryUv[2];
    const uint64_t key = terrain::seedKey(s.path);
    g.keyLo = static_cast<uint32_t>(key);
    g.keyHi = static_cast<uint32_t>(key >> 32);
    g.layer = s.imageryLayer;
    g.lodCount = s.lodCount;
    g.areaM2 = s.areaM2;
    g.nearestM = s.nearestM;
    g.previousUv01 = glm::vec4(s.previousUv[0], s.previousUv[1]);
    g.previousUv2 = s.previousUv[2];
    g.previousLayer = s.previousLayer;
    g.imageryBlend = s.imageryBlend;
    out.push_back(g);
  }
}

}  // namespace vegstream::scene
