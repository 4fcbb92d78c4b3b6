#pragma once
// createNamed: the four steps of every device object render/ makes: one vkCreate* call, its
// result checked (vk_check.h), the new handle named for the validation layers and debuggers
// (Context::setName), and owned (handle.h).

#include <string>
#include <utility>

#include "render/context.h"
#include "render/handle.h"
#include "render/vk_check.h"

namespace vegstream::render {

// create(&raw) is the vkCreate* call (`what` names it in the error it throws); the handle it
// makes is named `name` as an object of `type` and owned by an Owner on ctx's device.
template <class Owner, class Create>
Owner createNamed(const Context& ctx, VkObjectType type, const std::string& name, const char* what, Create&& create) {
  decltype(std::declval<const Owner&>().get()) raw = VK_NULL_HANDLE;
  vkCheck(create(&raw), what);
  ctx.setName(type, raw, name);
  return Owner(ctx.device(), raw);
}

// The usual form: create(device, &info, nullptr, &raw), e.g. vkCreateSampler with its
// VkSamplerCreateInfo.
template <class Owner, class Info, class Raw>
Owner createNamed(const Context& ctx, VkObjectType type, const std::string& name, const char* what,
                  VkResult (*create)(VkDevice, const Info*, const VkAllocationCallbacks*, Raw*), const Info& info) {
  return createNamed<Owner>(ctx, type, name, what, [&](Raw* raw) { return create(ctx.device(), &info, nullptr, raw); });
}

}  // namespace vegstream::render
