// A dataset opened for a lon/lat box (box_dataset.h).
#include "scene/box_dataset.h"

#include <cstdio>

#include "scene/dataset_calibration.h"
#include "streaming/open_tile_source.h"

namespace vegstream::scene {
namespace {

std::string degrees(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6f", v);
  return buf;
}

}  // namespace

Result<BoxDataset> openBoxDataset(const std::string& dataset, const geo::GeoBounds& box, const std::string& boxName,
                                  const vegetation::SpeciesCatalog& catalog) {
  auto source = streaming::openTileSource(dataset, {});
  if (!source) return source.error();
  auto meta = streaming::readMetaFrom(**source);
  if (!meta) return meta.error();
  if (!meta->imagery)
    return makeError(ErrorKind::InvalidInput,
                     "dataset " + dataset + " has no imagery: species come from the imagery colour");
  const geo::GeoBounds& b = meta->bounds;
  if (b.crossesAntimeridian())
    return makeError(ErrorKind::Unsupported, "dataset " + dataset + " crosses the antimeridian: not supported");
  if (box.westDeg < b.westDeg || box.eastDeg > b.eastDeg || box.southDeg < b.southDeg || box.northDeg > b.northDeg)
    return makeError(ErrorKind::InvalidInput, boxName + ": not inside the dataset's bounds (lon " + degrees(b.westDeg) +
                                                  " … " + degrees(b.eastDeg) + ", lat " + degrees(b.southDeg) + " … " +
                                                  degrees(b.northDeg) + ")");
  vegetation::SpeciesCatalog calibrated = calibratedCatalog(catalog, *meta);
  const geo::LocalFrame frame({0.5 * (b.southDeg + b.northDeg), b.centre().x, 0.0});
  return BoxDataset{std::move(*source), std::move(*meta), std::move(calibrated), frame};
}

}  // namespace vegstream::scene
