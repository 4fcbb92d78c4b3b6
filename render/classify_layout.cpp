// Packing the species catalog for the classify pass (classify_layout.h).
#include "render/classify_layout.h"

#include <cassert>
#include <cmath>

#include "vegetation/colour_score.h"

namespace vegstream::render {

SpeciesBlock packSpecies(const vegetation::SpeciesCatalog& catalog) {
  assert(catalog.species.size() <= vegetation::kMaxSpecies);
  SpeciesBlock b;
  b.count[0] = static_cast<uint32_t>(catalog.species.size());
  b.calibration = catalog.calibration.rows;
  for (size_t code = 0; code < 256; ++code)
    b.landcoverMasks[code / 4][code % 4] = catalog.landcoverCodes ? (*catalog.landcoverCodes)[code] : vegetation::kAllSpecies;
  for (size_t i = 0; i < catalog.species.size(); ++i) {
    const vegetation::Species& s = catalog.species[i];
    SpeciesGpu& g = b.species[i];
    g.reference = glm::vec4(s.score.reference, s.score.p);
    // ln threshold; +1e30 keeps out a tree species that does not claim ground (species_choice.h).
    const bool out = vegetation::isTree(s) && !s.tree.claimsGround;
    g.weights = glm::vec4(s.score.weights, out ? 1e30f : s.threshold > 0.0f ? std::log(s.threshold) : -1e30f);
    // Tree species are seeded on their own grid (vegetation/tree_placement.h): to the plants' classify
    // pass they are bare soil (vegetation/plant_seeding.cpp rejects them alike).
    g.flags = {(s.bare || vegetation::isTree(s)) ? 1u : 0u, static_cast<uint32_t>(s.kind), s.shadows ? 1u : 0u,
               vegetation::isTree(s) ? 1u : 0u};
    g.marker.w = s.phototropism;
    g.ground = {s.densityM2, s.horizonM, s.score.ndviReference, s.score.ndviWeight};
    g.index = {s.score.exgReference, s.score.exgWeight, 0.0f, 0.0f};
    g.heightStiffness = {s.heightM.min, s.heightM.max, s.stiffness.min, s.stiffness.max};
    g.widthColour = {s.widthM.min, s.widthM.max, s.colourModulation.min, s.colourModulation.max};
    // Markers in the species' own reference colour, brightened so dark species stay visible.
    glm::vec3 hsv = s.score.reference;
    hsv.z = std::max(hsv.z, 0.55f);
    hsv.y = std::max(hsv.y, 0.5f);
    const glm::vec3 srgb = vegetation::srgbFromHsv(hsv);
    g.marker = glm::vec4(vegetation::srgbDecode(srgb.r), vegetation::srgbDecode(srgb.g), vegetation::srgbDecode(srgb.b),
                         s.phototropism);
  }
  return b;
}

}  // namespace vegstream::render
