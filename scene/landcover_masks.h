#pragma once
// The species each landcover class code allows (issue 41, item 2): the dataset's scheme maps a
// code to its kind (datasets/landcover_classes.h), the catalog's landcover table a kind to its
// species (vegetation/landcover_species.h). Mapped here, in scene/, because vegetation/ does not
// see datasets/ (DESIGN.md's folder order).
//
//   code 0 (no class there)        every species: the colour alone chooses, as without the layer
//   a class of the scheme          allowedSpecies(catalog, its kind)
//   a code the scheme does not know  no species: it grows nothing (the importer warned, once, with
//                                  its pixel count: datasets/landcover_classes.h)

#include <array>
#include <cstdint>

#include "datasets/landcover_classes.h"
#include "vegetation/species_catalog.h"

namespace vegstream::scene {

using LandcoverMasks = std::array<vegetation::SpeciesMask, 256>;

LandcoverMasks landcoverMasks(const vegetation::SpeciesCatalog& catalog, datasets::LandcoverScheme scheme);

}  // namespace vegstream::scene
