// Overflow thinning (vegetation/overflow_thinning.h): no thinning without pressure, sizes that
// change by a bounded amount when the pressure does (no pop), a pressure continuous in the
// groups wanted that keeps the groups appended under the buffer, and priorities spread evenly.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/hash.h"
#include "vegetation/overflow_thinning.h"

namespace vegstream::vegetation {
namespace {

TEST(OverflowThinning, WithoutPressureEveryGroupIsWhole) {
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(thinningFade(0.0f, static_cast<float>(i) / 1000.0f), 1.0f);
  EXPECT_EQ(thinningPressure(0, 100), 0.0f);
  EXPECT_EQ(thinningPressure(75, 100), 0.0f);
}

TEST(OverflowThinning, APressureStepChangesNoGroupByMoreThanItsBandAllows) {
  // Sizes move by at most Δp (1 + b) / b: a 0.4 % change of the groups wanted per frame
  // (a slow flight) changes no group by more than 2 %.
  const float dp = 0.004f * (1.0f - 0.3f);
  float worst = 0.0f;
  for (int i = 0; i < 1000; ++i) {
    const float u = static_cast<float>(i) / 1000.0f;
    worst = std::max(worst, std::abs(thinningFade(0.3f + dp, u) - thinningFade(0.3f, u)));
  }
  EXPECT_LE(worst, dp * (1.0f + kThinningBand) / kThinningBand + 1e-6f);
  EXPECT_LT(worst, 0.02f);
  // The pressure itself is continuous in the groups wanted (no step where thinning starts).
  EXPECT_NEAR(thinningPressure(751, 1000), 0.0f, 2e-3f);
  EXPECT_LT(thinningPressure(1004, 1000) - thinningPressure(1000, 1000), 0.004f);
}

TEST(OverflowThinning, TheGroupsAppendedStayUnderTheCapacity) {
  for (uint64_t wanted : {100u, 800u, 1000u, 1300u, 5000u, 100000u}) {
    const float p = thinningPressure(wanted, 1000);
    uint64_t appended = 0;
    for (uint64_t g = 0; g < wanted; ++g)
      appended += thinningFade(p, groupPriority(mix32(static_cast<uint32_t>(g)) * 0x100000001ull, 1, 0)) > 0.0f;
    EXPECT_LE(appended, 1000u) << wanted << " wanted";
    if (wanted >= 1300) {
      EXPECT_GT(appended, 850u) << wanted << " wanted";
    }
  }
}

TEST(OverflowThinning, ASeedsPrioritiesSpreadOverTheRange) {
  // The seeds of one cluster 0 are spread (golden-ratio steps), not one shared priority.
  for (uint64_t key : {1ull, 0x1234567890abcdefull}) {
    int low = 0;
    for (uint32_t s = 0; s < 8; ++s) low += groupPriority(key, 0, s) < 0.5f;
    EXPECT_GE(low, 3);
    EXPECT_LE(low, 5);
  }
}

}  // namespace
}  // namespace vegstream::vegetation
