// The validation plumbing itself: an invalid call must reach the ValidationLog, otherwise
// "the layers stayed silent" in every other test would prove nothing.

#include <gtest/gtest.h>

#include "render/context.h"

namespace vegstream::render {
namespace {

TEST(Validation, AnInvalidCallIsReportedAsAnError) {
  auto log = std::make_shared<ValidationLog>();
  ContextOptions o;
  o.validate = true;
  o.validationLog = log;
  auto ctx = Context::create(o);
  ASSERT_TRUE(ctx.ok()) << ctx.error().message;
  ASSERT_TRUE((*ctx)->validationEnabled());
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = 0;  // invalid: VUID-VkBufferCreateInfo-size-00912
  bci.usage = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  const VkResult result = vkCreateBuffer((*ctx)->device(), &bci, nullptr, &buffer);
  if (result == VK_SUCCESS && buffer) vkDestroyBuffer((*ctx)->device(), buffer, nullptr);
  EXPECT_GE(log->errors(), 1);
  ASSERT_FALSE(log->messages().empty());
  EXPECT_NE(log->messages().front().find("size"), std::string::npos);
}

TEST(Validation, OffUnlessAskedFor) {
  auto ctx = Context::create({});
  ASSERT_TRUE(ctx.ok());
  EXPECT_FALSE((*ctx)->validationEnabled());
}

}  // namespace
}  // namespace vegstream::render
