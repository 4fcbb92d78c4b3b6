// Which species each landcover kind allows (landcover_species.h: the default from the species'
// kinds, the catalog's table read by species_catalog.cpp).
#include "vegetation/landcover_species.h"

#include "vegetation/species_catalog.h"

namespace vegstream::vegetation {

LandcoverTable defaultLandcoverTable(const std::vector<Species>& species) {
  LandcoverTable t{};
  for (size_t i = 0; i < species.size() && i < 32; ++i) {
    const Species& s = species[i];
    const SpeciesMask bit = SpeciesMask{1} << i;
    const bool bare = s.bare, tree = isTree(s);
    const bool herb = !bare && (s.kind == RendererKind::Grass || s.kind == RendererKind::Flowers);
    const bool gravel = !bare && s.kind == RendererKind::Gravel;
    auto allow = [&](LandcoverKind k, bool yes) {
      if (yes) t[static_cast<size_t>(k)] |= bit;
    };
    allow(LandcoverKind::Tree, tree || bare);
    allow(LandcoverKind::Grass, herb || bare);
    allow(LandcoverKind::Crop, herb || bare);
    allow(LandcoverKind::Wetland, herb || bare);
    allow(LandcoverKind::Shrub, herb || gravel || bare);
    allow(LandcoverKind::Bare, gravel || bare);
    // Built, Water, Snow: nothing.
  }
  return t;
}

SpeciesMask allowedSpecies(const SpeciesCatalog& catalog, LandcoverKind kind) {
  const LandcoverTable t = catalog.landcover ? *catalog.landcover : defaultLandcoverTable(catalog.species);
  return t[static_cast<size_t>(kind)];
}

}  // namespace vegstream::vegetation
