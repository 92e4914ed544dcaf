#pragma once
// Checks every Vulkan call: a failure throws vt::Error naming the call, the place and the result.
#include <vulkan/vulkan.h>

namespace vt::renderer {

/// The enum name of a VkResult ("VK_ERROR_DEVICE_LOST"); any thread.
const char* resultName(VkResult result) noexcept;

/// Throws vt::Error "<call> failed: <result> (<file>:<line>)" unless result is VK_SUCCESS
/// (or another non-error code listed by the caller's logic); returns the result otherwise.
VkResult checkVk(VkResult result, const char* call, const char* file, int line);

}  // namespace vt::renderer

/// Wraps a Vulkan call returning VkResult; negative (error) results throw vt::Error.
#define VT_VK(call) ::vt::renderer::checkVk((call), #call, __FILE__, __LINE__)
