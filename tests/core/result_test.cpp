#include "core/result.h"

#include <gtest/gtest.h>

namespace vegstream {
namespace {

Result<int> parsePositive(int v) {
  if (v <= 0) return makeError(ErrorKind::InvalidInput, "value must be positive");
  return v;
}

TEST(Result, CarriesValueOrError) {
  auto good = parsePositive(3);
  ASSERT_TRUE(good.ok());
  EXPECT_EQ(*good, 3);
  auto bad = parsePositive(-1);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().kind, ErrorKind::InvalidInput);
  EXPECT_TRUE(bad.error().isUserError());
  EXPECT_FALSE(makeError(ErrorKind::Gpu, "x").isUserError());
}

TEST(Result, StatusDefaultsToOk) {
  Status s;
  EXPECT_TRUE(s.ok());
  Status f = makeError(ErrorKind::Io, "disk full");
  EXPECT_FALSE(f.ok());
  EXPECT_EQ(f.error().message, "disk full");
}

}  // namespace
}  // namespace vegstream
