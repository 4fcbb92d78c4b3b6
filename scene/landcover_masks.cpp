// Class code → allowed species (landcover_masks.h).
#include "scene/landcover_masks.h"

namespace vegstream::scene {

LandcoverMasks landcoverMasks(const vegetation::SpeciesCatalog& catalog, datasets::LandcoverScheme scheme) {
  LandcoverMasks masks{};  // unknown codes: 0, nothing grows
  masks[0] = vegetation::kAllSpecies;
  for (const datasets::LandcoverClass& c : datasets::landcoverClasses(scheme))
    masks[c.code] = vegetation::allowedSpecies(catalog, c.kind);
  return masks;
}

}  // namespace vegstream::scene
