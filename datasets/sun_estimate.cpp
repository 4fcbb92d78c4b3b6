// Estimating the acquisition sun from imagery and DEM normals (sun_estimate.h): least squares
// of log-brightness against the shading model of deshading.h, a per-block intercept absorbing
// the albedo, minimised over the sun direction by grid search and pattern search.

#include "datasets/sun_estimate.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "datasets/message.h"

namespace vegstream::datasets {
namespace {

constexpr double kMinElevationDeg = 5.0, kMaxElevationDeg = 85.0;

class Fit {
 public:
  Fit(const std::vector<ShadingSample>& samples, double k) : samples_(samples), k_(k) {
    uint32_t groups = 0;
    for (const auto& s : samples) groups = std::max(groups, s.group + 1);
    sum_.resize(groups);
    sq_.resize(groups);
    n_.resize(groups);
  }

  // Within-group sum of squared residuals of log B − log shading(sun); no shading at all when
  // `sun` is null.
  double sse(const SunAngles* sun) {
    std::fill(sum_.begin(), sum_.end(), 0.0);
    std::fill(sq_.begin(), sq_.end(), 0.0);
    std::fill(n_.begin(), n_.end(), 0u);
    const glm::dvec3 s = sun ? sunVectorEnu(*sun) : glm::dvec3(0.0);
    for (const auto& x : samples_) {
      const double r = x.logBrightness - (sun ? std::log(shading(glm::dvec3(x.normal), s, k_)) : 0.0);
      sum_[x.group] += r;
      sq_[x.group] += r * r;
      ++n_[x.group];
    }
    double total = 0.0;
    for (size_t g = 0; g < sum_.size(); ++g)
      if (n_[g]) total += sq_[g] - sum_[g] * sum_[g] / n_[g];
    return total;
  }

 private:
  const std::vector<ShadingSample>& samples_;
  double k_;
  std::vector<double> sum_, sq_;
  std::vector<uint32_t> n_;
};

SunAngles clampSun(SunAngles s) {
  s.azimuthDeg = std::fmod(std::fmod(s.azimuthDeg, 360.0) + 360.0, 360.0);
  s.elevationDeg = std::clamp(s.elevationDeg, kMinElevationDeg, kMaxElevationDeg);
  return s;
}

// The best sun on a 5° grid.
SunAngles gridSearch(Fit& fit, double& best) {
  SunAngles arg{0.0, 45.0};
  best = INFINITY;
  for (double el = kMinElevationDeg; el <= kMaxElevationDeg + 1e-9; el += 5.0)
    for (double az = 0.0; az < 360.0; az += 5.0) {
      const SunAngles s{az, el};
      const double e = fit.sse(&s);
      if (e < best) {
        best = e;
        arg = s;
      }
    }
  return arg;
}

// Pattern search from `start`: the eight neighbours at ± step, moving while one is better,
// halving the step otherwise, down to 0.1°.
SunAngles refine(Fit& fit, SunAngles at, double& best) {
  for (double step = 2.5; step >= 0.1; step /= 2.0) {
    for (bool moved = true; moved;) {
      moved = false;
      for (int da = -1; da <= 1; ++da)
        for (int de = -1; de <= 1; ++de) {
          if (!da && !de) continue;
          const SunAngles s = clampSun({at.azimuthDeg + da * step, at.elevationDeg + de * step});
          const double e = fit.sse(&s);
          if (e < best - 1e-12) {
            best = e;
            at = s;
            moved = true;
          }
        }
    }
  }
  return at;
}

}  // namespace

SunEstimate estimateSun(const std::vector<ShadingSample>& samples, double k) {
  SunEstimate out;
  const float sloped = static_cast<float>(std::cos(5.0 * 3.14159265358979323846 / 180.0));
  size_t steep = 0;
  for (const auto& s : samples) steep += s.normal.z < sloped;
  if (samples.empty() || static_cast<double>(steep) < kMinSlopedFraction * static_cast<double>(samples.size())) {
    out.note = concat("terrain too flat to estimate the sun (", steep, " of ", samples.size(),
                      " samples steeper than 5 degrees): not de-shaded");
    return out;
  }
  Fit fit(samples, k);
  const double none = fit.sse(nullptr);
  double best = 0.0;
  out.sun = refine(fit, gridSearch(fit, best), best);
  out.explained = none > 0.0 ? 1.0 - best / none : 0.0;
  const int pct = static_cast<int>(std::lround(out.explained * 100.0));
  if (out.explained < kMinExplainedVariance) {
    out.note = concat("the best-fitting sun explains only ", pct, " % of the brightness variance: not de-shaded");
    return out;
  }
  out.found = true;
  out.note = concat("least squares of log-brightness over ", samples.size(), " samples; the shading explains ", pct,
                    " % of its variance within 64-pixel blocks");
  return out;
}

}  // namespace vegstream::datasets
