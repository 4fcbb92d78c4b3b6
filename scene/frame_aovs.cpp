// The measurement AOVs beside a still (frame_aovs.h).

#include "scene/frame_aovs.h"

#include <sstream>
#include <vector>

#include "render/tiff_writer.h"

namespace vegstream::scene {
namespace fs = std::filesystem;

Result<AovSelection> parseAovList(const std::string& list, const std::string& option) {
  AovSelection s;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    bool* flag = name == "depth" ? &s.depth : name == "coverage" ? &s.coverage : name == "species" ? &s.species : nullptr;
    if (!flag)
      return makeError(ErrorKind::InvalidInput, option + " " + list + ": no AOV named '" + name +
                                                    "'; each must be one of depth, coverage, species (comma-separated)");
    if (*flag) return makeError(ErrorKind::InvalidInput, option + " " + list + ": '" + name + "' must be named once");
    *flag = true;
  }
  if (!list.empty() && list.back() == ',')
    return makeError(ErrorKind::InvalidInput, option + " " + list + ": no AOV named ''; each must be one of depth, coverage, species");
  return s;
}

fs::path aovPathFor(const fs::path& png, const std::string& name) {
  fs::path out = png;
  return out.replace_extension("." + name + ".tif");
}

Status writeFrameAovs(const fs::path& png, const render::AovImage& aov, const AovSelection& which) {
  const struct {
    bool wanted;
    const char* name;
    const std::vector<float>& values;
  } planes[] = {{which.depth, "depth", aov.distanceM},
                {which.coverage, "coverage", aov.coverage},
                {which.species, "species", aov.species}};
  std::vector<fs::path> written;
  for (const auto& p : planes) {
    if (!p.wanted) continue;
    const fs::path path = aovPathFor(png, p.name);
    if (Status s = render::writeFloatTiff(path, aov.width, aov.height, p.values); !s) {
      std::error_code ec;
      for (const fs::path& w : written) fs::remove(w, ec);
      return s;
    }
    written.push_back(path);
  }
  return {};
}

}  // namespace vegstream::scene
