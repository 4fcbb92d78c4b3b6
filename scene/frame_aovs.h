#pragma once
// The measurement AOVs beside a still F.png (issue 39: `snapshot --aov`, `record --aov` for the
// frames it saves): one-channel 32-bit float TIFFs
//   F.depth.tif     metres from the camera to what the pixel shows (its first sample), 0 for sky;
//   F.coverage.tif  0 … 1, the share of the pixel's samples covered by plants or trees;
//   F.species.tif   the catalog index + 1 of the vegetation there, 0 for none
// (render/aov_image.h: how an AOV frame makes them).

#include <filesystem>
#include <string>

#include "core/result.h"
#include "render/frame_types.h"

namespace vegstream::scene {

struct AovSelection {
  bool depth = false, coverage = false, species = false;
  bool any() const { return depth || coverage || species; }
};

// `list`: comma-separated names out of depth, coverage, species (each at most once; "" selects
// none). An InvalidInput error names `option` and the name that is wrong.
Result<AovSelection> parseAovList(const std::string& list, const std::string& option = "--aov");

// F.<name>.tif for F.png.
std::filesystem::path aovPathFor(const std::filesystem::path& png, const std::string& name);

// Writes the selected AOVs of `aov` beside `png`, each atomically; when one fails, those this
// call wrote are removed again and the error names the file.
Status writeFrameAovs(const std::filesystem::path& png, const render::AovImage& aov, const AovSelection& which);

}  // namespace vegstream::scene
