#pragma once
// The coarse kinds of ground a landcover class stands for (issue 41, item 2). They live in core/
// because two folders that must not see each other use them: datasets/ maps each scheme's class
// codes to a kind (datasets/landcover_classes.h), vegetation/ says which species each kind
// allows (vegetation/species_catalog.h's landcover table). The values index tables (0 … 8).

#include <cstddef>

namespace vegstream {

enum class LandcoverKind { Tree, Shrub, Grass, Crop, Bare, Built, Water, Snow, Wetland };
inline constexpr size_t kLandcoverKindCount = 9;

// "tree", "shrub", "grass", "crop", "bare", "built", "water", "snow", "wetland" (the landcover
// table's keys in the species catalog, `query`'s landcover.kind).
inline const char* landcoverKindName(LandcoverKind k) {
  constexpr const char* kNames[kLandcoverKindCount] = {"tree",  "shrub", "grass", "crop",   "bare",
                                                      "built", "water", "snow",  "wetland"};
  return kNames[static_cast<size_t>(k)];
}

}  // namespace vegstream
