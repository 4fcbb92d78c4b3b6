// Device selection: the best device by type, --device by name, a clear error otherwise.

#include <algorithm>

#include "gpu_test_fixture.h"
#include "render/context.h"

namespace vegstream::render::testing {
namespace {

int rank(const std::string& type) {
  if (type == "discrete") return 4;
  if (type == "integrated") return 3;
  if (type == "virtual") return 2;
  if (type == "cpu") return 1;
  return 0;
}

TEST(Devices, ListsAtLeastOneDeviceWithSampleCounts) {
  auto devices = listDevices();
  ASSERT_TRUE(devices.ok()) << devices.error().message;
  ASSERT_FALSE(devices->empty());
  for (const auto& d : *devices) {
    EXPECT_FALSE(d.name.empty());
    EXPECT_TRUE(d.supportsMsaa(1)) << d.name;  // every device offers single-sampled targets
  }
}

class DeviceSelection : public GpuTest {};

TEST_F(DeviceSelection, PrefersTheHighestRankedDevice) {
  auto devices = listDevices();
  ASSERT_TRUE(devices.ok());
  int best = 0;
  for (const auto& d : *devices) best = std::max(best, rank(d.type));
  auto r = makeRenderer(64, 36, 1);
  ASSERT_TRUE(r);
  EXPECT_EQ(rank(r->device().type), best) << r->device().name;
  EXPECT_EQ(r->device().software, r->device().type == "cpu");
}

TEST_F(DeviceSelection, ChoosesByCaseInsensitiveNameSubstring) {
  auto devices = listDevices();
  ASSERT_TRUE(devices.ok());
  const std::string wanted = devices->back().name;
  std::string upper = wanted.substr(0, 6);
  std::transform(upper.begin(), upper.end(), upper.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  auto o = options(64, 36, 1);
  o.context.deviceName = upper;
  auto r = Renderer::create(o);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_NE((*r)->device().name.find(wanted.substr(0, 6)), std::string::npos);
}

TEST_F(DeviceSelection, UnknownNameIsAUserErrorListingTheDevices) {
  auto o = options(64, 36, 1);
  o.context.deviceName = "no-such-gpu-9000";
  auto r = Renderer::create(o);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::NotFound);
  EXPECT_TRUE(r.error().isUserError());
  EXPECT_NE(r.error().message.find("no-such-gpu-9000"), std::string::npos);
  EXPECT_NE(r.error().message.find("available"), std::string::npos);
}

TEST_F(DeviceSelection, UnofferedMsaaAndImpossibleSizeAreUserErrors) {
  auto devices = listDevices();
  ASSERT_TRUE(devices.ok());
  int unoffered = 0;
  for (int s : {2, 8, 16})
    if (!devices->front().supportsMsaa(s)) unoffered = s;
  if (unoffered != 0) {
    auto o = options(64, 36, unoffered);
    o.context.deviceName = devices->front().name;
    auto r = Renderer::create(o);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
    EXPECT_NE(r.error().message.find("--msaa"), std::string::npos);
  }
  auto r = Renderer::create(options(0, 36, 1));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("--size"), std::string::npos);
  auto huge = Renderer::create(options(1u << 20, 36, 1));
  ASSERT_FALSE(huge.ok());
  EXPECT_EQ(huge.error().kind, ErrorKind::InvalidInput);
}

}  // namespace
}  // namespace vegstream::render::testing
