#include "vt/renderer/vk_check.hpp"

#include "vt/core/error.hpp"

namespace vt::renderer {

const char* resultName(VkResult result) noexcept {
  switch (result) {
#define VT_CASE(x) case x: return #x;
    VT_CASE(VK_SUCCESS)
    VT_CASE(VK_NOT_READY)
    VT_CASE(VK_TIMEOUT)
    VT_CASE(VK_EVENT_SET)
    VT_CASE(VK_EVENT_RESET)
    VT_CASE(VK_INCOMPLETE)
    VT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    VT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    VT_CASE(VK_ERROR_INITIALIZATION_FAILED)
    VT_CASE(VK_ERROR_DEVICE_LOST)
    VT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    VT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    VT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    VT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    VT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    VT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    VT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    VT_CASE(VK_ERROR_FRAGMENTED_POOL)
    VT_CASE(VK_ERROR_UNKNOWN)
    VT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    VT_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    VT_CASE(VK_ERROR_FRAGMENTATION)
    VT_CASE(VK_ERROR_SURFACE_LOST_KHR)
    VT_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
    VT_CASE(VK_SUBOPTIMAL_KHR)
    VT_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    VT_CASE(VK_ERROR_INCOMPATIBLE_DISPLAY_KHR)
    VT_CASE(VK_ERROR_VALIDATION_FAILED_EXT)
#undef VT_CASE
    default: return "VkResult(unknown)";
  }
}

VkResult checkVk(VkResult result, const char* call, const char* file, int line) {
  if (result < 0) fail(call, " failed: ", resultName(result), " (", result, ") at ", file, ":", line);
  return result;
}

}  // namespace vt::renderer
