// Packing the species catalog for the classify pass (classify_layout.h).
#include "render/classify_layout.h"

#include <cassert>
#include <cmath>

#include "vegetation/colour_score.h"

namespace vegstream::render {
namespace {

// HSV (hexcone) → sRGB-encoded RGB: the inverse of vegetation::hsvFromSrgb.
glm::vec3 srgbFromHsv(glm::vec3 hsv) {
  const float h6 = hsv.x * 6.0f, c = hsv.z * hsv.y, x = c * (1.0f - std::abs(std::fmod(h6, 2.0f) - 1.0f));
  const glm::vec3 sectors[] = {{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}};
  return sectors[static_cast<int>(h6) % 6] + (hsv.z - c);
}

}  // namespace

SpeciesBlock packSpecies(const vegetation::SpeciesCatalog& catalog) {
  assert(catalog.species.size() <= vegetation::kMaxSpecies);
  SpeciesBlock b;
  b.count[0] = static_cast<uint32_t>(catalog.species.size());
  for (size_t i = 0; i < catalog.species.size(); ++i) {
    const vegetation::Species& s = catalog.species[i];
    SpeciesGpu& g = b.species[i];
    g.reference = glm::vec4(s.score.reference, s.score.p);
    g.weights = glm::vec4(s.score.weights, s.threshold > 0.0f ? std::log(s.threshold) : -1e30f);
    g.flags = {s.bare ? 1u : 0u, static_cast<uint32_t>(s.kind), 0u, 0u};
    g.marker.w = s.phototropism;
    g.heightStiffness = {s.heightM.min, s.heightM.max, s.stiffness.min, s.stiffness.max};
    g.widthColour = {s.widthM.min, s.widthM.max, s.colourModulation.min, s.colourModulation.max};
    // Markers in the species' own reference colour, brightened so dark species stay visible.
    glm::vec3 hsv = s.score.reference;
    hsv.z = std::max(hsv.z, 0.55f);
    hsv.y = std::max(hsv.y, 0.5f);
    const glm::vec3 srgb = srgbFromHsv(hsv);
    g.marker = glm::vec4(vegetation::srgbDecode(srgb.r), vegetation::srgbDecode(srgb.g), vegetation::srgbDecode(srgb.b),
                         s.phototropism);
  }
  return b;
}

}  // namespace vegstream::render
