#pragma once
// The synthetic dataset (`vegstream generate`): fractal relief and biome colours, fully
// georeferenced, written in the same dataset format as an import — the embedded default when
// no real data is at hand, and a dataset of any size for tests and benchmarks.
//
// Relief: domain-warped gradient-noise fBm selects mountain and valley regions; ridged
// multifractal noise raises the mountains. Colours follow height and slope: grass in the
// valleys, forest on the lower slopes, alpine meadow above the tree line, rock on steep slopes,
// snow high up. Everything is a pure function of the seed and the position in metres from the
// centre, so the same seed gives identical tile files and tiles agree along their borders.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <array>

#include "core/log.h"
#include "core/result.h"
#include "core/task_runner.h"
#include "datasets/dataset_format.h"
#include "datasets/xyz_import.h"

namespace vegstream::datasets {

struct SyntheticOptions {
  std::filesystem::path out;
  std::string name;             // empty: the last component of `out`
  double centreLatDeg = 46.55;  // an alpine valley-and-ridge setting (Bernese Oberland latitudes)
  double centreLonDeg = 7.95;
  double sizeKm = 10.0;  // side of the square area, 0.1 … 200
  uint64_t seed = 1;
  // Finest zoom; 0: the coarsest zoom whose pixels are at most 10 m on the ground.
  int maxZoom = 0;
  std::optional<int> minZoom;  // nullopt: down to the zoom at which the area fits one tile
  ElevationEncoding encoding = ElevationEncoding::Terrarium;
  int threads = 0;              // 0: all cores
  TaskRunner* tasks = nullptr;  // runs the workers (outlives the call); null: a pool made for the call
};

// The terrain itself, for tests and for code that wants the continuous field.
class SyntheticTerrain {
 public:
  explicit SyntheticTerrain(uint64_t seed);
  // Height in metres at (east, north) metres from the dataset centre.
  double heightM(double eastM, double northM) const;
  // Base colour from height, slope (radians) and position (for patchiness).
  std::array<uint8_t, 3> color(double eastM, double northM, double heightM, double slopeRad) const;

 private:
  uint32_t seed_[4];
};

// The area the options describe (a square of sizeKm around the centre).
geo::GeoBounds syntheticBounds(const SyntheticOptions& options);

// Writes the dataset (through a temporary directory, renamed into place). Errors: InvalidInput
// for bad options (names the option), Io when `out` cannot be written.
Result<DatasetMeta> generateSyntheticDataset(const SyntheticOptions& options, const Logger& log,
                                             ProgressSink& progress);

}  // namespace vegstream::datasets
