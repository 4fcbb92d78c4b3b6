// Clark & Evans (1954) aggregation index with Donnelly's (1978) edge correction, and the
// coefficient of variation (stand_statistics.h).
#include "vegetation/stand_statistics.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <vector>

namespace vegstream::vegetation {

ClarkEvans clarkEvans(std::span<const glm::dvec2> points, double x0, double y0, double x1, double y1) {
  assert(x0 < x1 && y0 < y1);
  std::vector<glm::dvec2> in;
  for (const glm::dvec2& p : points)
    if (p.x >= x0 && p.x < x1 && p.y >= y0 && p.y < y1) in.push_back(p);
  ClarkEvans out;
  out.n = in.size();
  if (in.size() < 2) return out;
  const double area = (x1 - x0) * (y1 - y0), perimeter = 2.0 * ((x1 - x0) + (y1 - y0));
  const double n = double(in.size());
  // Buckets of about two points each; the nearest neighbour is searched in growing rings.
  const double bucket = std::sqrt(2.0 * area / n);
  const auto nx = static_cast<int64_t>(std::ceil((x1 - x0) / bucket)), ny = static_cast<int64_t>(std::ceil((y1 - y0) / bucket));
  std::vector<std::vector<size_t>> grid(static_cast<size_t>(nx * ny));
  auto bx = [&](double x) { return std::clamp<int64_t>(static_cast<int64_t>((x - x0) / bucket), 0, nx - 1); };
  auto by = [&](double y) { return std::clamp<int64_t>(static_cast<int64_t>((y - y0) / bucket), 0, ny - 1); };
  for (size_t i = 0; i < in.size(); ++i) grid[static_cast<size_t>(by(in[i].y) * nx + bx(in[i].x))].push_back(i);
  double sum = 0.0;
  for (size_t i = 0; i < in.size(); ++i) {
    const int64_t cx = bx(in[i].x), cy = by(in[i].y);
    double best = std::numeric_limits<double>::infinity();
    // Ring k holds every point within k · bucket: stop once the best is inside the searched square.
    for (int64_t k = 0; k <= std::max(nx, ny) && !(best <= double(k - 1) * bucket); ++k)
      for (int64_t y = cy - k; y <= cy + k; ++y)
        for (int64_t x = cx - k; x <= cx + k; ++x) {
          if (std::max(std::abs(x - cx), std::abs(y - cy)) != k || x < 0 || y < 0 || x >= nx || y >= ny) continue;
          for (size_t j : grid[static_cast<size_t>(y * nx + x)])
            if (j != i) best = std::min(best, std::hypot(in[i].x - in[j].x, in[i].y - in[j].y));
        }
    sum += best;
  }
  out.meanNearestM = sum / n;
  out.expectedM = 0.5 * std::sqrt(area / n) + (0.0514 + 0.041 / std::sqrt(n)) * perimeter / n;
  out.r = out.meanNearestM / out.expectedM;
  return out;
}

double coefficientOfVariation(std::span<const double> values) {
  if (values.size() < 2) return 0.0;
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= double(values.size());
  if (mean == 0.0) return 0.0;
  double var = 0.0;
  for (double v : values) var += (v - mean) * (v - mean);
  var /= double(values.size() - 1);
  return std::sqrt(var) / std::abs(mean);
}

}  // namespace vegstream::vegetation
