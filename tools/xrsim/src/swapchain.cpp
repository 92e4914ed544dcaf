// Swapchains: images on the application's device, acquire / wait / release in order.
#include <algorithm>

#include "api.hpp"
#include "vulkan.hpp"

namespace xrsim {

XrResult XRAPI_CALL enumerateSwapchainFormats(XrSession handle, std::uint32_t capacity, std::uint32_t* count,
                                              std::int64_t* out) {
  return guarded("xrEnumerateSwapchainFormats", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    std::vector<std::int64_t> formats;
    for (VkFormat f : supportedFormats(session->physicalDevice)) formats.push_back(std::int64_t(f));
    return twoCall(capacity, count, out, formats);
  });
}

XrResult XRAPI_CALL createSwapchain(XrSession handle, const XrSwapchainCreateInfo* info, XrSwapchain* out) {
  return guarded("xrCreateSwapchain", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_SWAPCHAIN_CREATE_INFO);
    if (out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    const auto formats = supportedFormats(session->physicalDevice);
    if (std::find(formats.begin(), formats.end(), VkFormat(info->format)) == formats.end())
      return XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED;
    if (info->width == 0 || info->height == 0 || info->width > 4096 || info->height > 4096 || info->arraySize == 0 ||
        info->mipCount == 0 || info->sampleCount != 1)
      return XR_ERROR_VALIDATION_FAILURE;
    if (info->faceCount != 1) return XR_ERROR_FEATURE_UNSUPPORTED;  // cube maps need XR_KHR_composition_layer_cube
    if (info->createFlags & XR_SWAPCHAIN_CREATE_PROTECTED_CONTENT_BIT) return XR_ERROR_FEATURE_UNSUPPORTED;
    const bool depth = isDepthFormat(VkFormat(info->format));
    if (depth && (info->usageFlags & XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT)) return XR_ERROR_FEATURE_UNSUPPORTED;
    if (!depth && (info->usageFlags & XR_SWAPCHAIN_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT)) return XR_ERROR_FEATURE_UNSUPPORTED;

    auto swapchain = std::make_unique<Swapchain>();
    swapchain->info = *info;
    swapchain->info.next = nullptr;
    swapchain->format = VkFormat(info->format);
    swapchain->session = session;
    createSwapchainImages(*session, *swapchain);
    *out = handleOf(swapchain.get());
    session->swapchains.push_back(std::move(swapchain));
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL destroySwapchain(XrSwapchain handle) {
  return guarded("xrDestroySwapchain", [&]() -> XrResult {
    Swapchain* swapchain = lookup<Swapchain>(handle);
    if (swapchain == nullptr) return XR_ERROR_HANDLE_INVALID;
    auto& list = swapchain->session->swapchains;
    list.erase(std::find_if(list.begin(), list.end(), [&](const auto& s) { return s.get() == swapchain; }));
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL enumerateSwapchainImages(XrSwapchain handle, std::uint32_t capacity, std::uint32_t* count,
                                             XrSwapchainImageBaseHeader* images) {
  return guarded("xrEnumerateSwapchainImages", [&]() -> XrResult {
    Swapchain* swapchain = lookup<Swapchain>(handle);
    if (swapchain == nullptr) return XR_ERROR_HANDLE_INVALID;
    Session* session = nullptr;
    if (XrResult r = findSession(handleOf(swapchain->session), session); r != XR_SUCCESS) return r;
    if (count == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    const auto n = std::uint32_t(swapchain->images.size());
    *count = n;
    if (capacity == 0) return XR_SUCCESS;
    if (capacity < n) return XR_ERROR_SIZE_INSUFFICIENT;
    if (images == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    auto* vk = reinterpret_cast<XrSwapchainImageVulkan2KHR*>(images);
    for (std::uint32_t i = 0; i < n; ++i) {
      if (vk[i].type != XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR) return XR_ERROR_VALIDATION_FAILURE;
      vk[i].image = swapchain->images[i];
    }
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL acquireSwapchainImage(XrSwapchain handle, const XrSwapchainImageAcquireInfo* info,
                                          std::uint32_t* index) {
  return guarded("xrAcquireSwapchainImage", [&]() -> XrResult {
    Swapchain* swapchain = lookup<Swapchain>(handle);
    if (swapchain == nullptr) return XR_ERROR_HANDLE_INVALID;
    Session* session = nullptr;
    if (XrResult r = findSession(handleOf(swapchain->session), session); r != XR_SUCCESS) return r;
    if (info != nullptr && info->type != XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO) return XR_ERROR_VALIDATION_FAILURE;
    if (index == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    const auto n = std::uint32_t(swapchain->images.size());
    const bool isStatic = swapchain->info.createFlags & XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT;
    if (swapchain->acquired.size() >= n) return XR_ERROR_CALL_ORDER_INVALID;
    if (isStatic && swapchain->lastReleased >= 0) return XR_ERROR_CALL_ORDER_INVALID;  // a static image is acquired once
    *index = swapchain->nextIndex;
    swapchain->acquired.push_back(swapchain->nextIndex);
    swapchain->nextIndex = (swapchain->nextIndex + 1) % n;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL waitSwapchainImage(XrSwapchain handle, const XrSwapchainImageWaitInfo* info) {
  return guarded("xrWaitSwapchainImage", [&]() -> XrResult {
    Swapchain* swapchain = lookup<Swapchain>(handle);
    if (swapchain == nullptr) return XR_ERROR_HANDLE_INVALID;
    Session* session = nullptr;
    if (XrResult r = findSession(handleOf(swapchain->session), session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
    if (swapchain->acquired.empty() || swapchain->waited) return XR_ERROR_CALL_ORDER_INVALID;
    // The compositor finished with the image inside xrEndFrame (capture waits on a fence).
    swapchain->waited = true;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL releaseSwapchainImage(XrSwapchain handle, const XrSwapchainImageReleaseInfo* info) {
  return guarded("xrReleaseSwapchainImage", [&]() -> XrResult {
    Swapchain* swapchain = lookup<Swapchain>(handle);
    if (swapchain == nullptr) return XR_ERROR_HANDLE_INVALID;
    Session* session = nullptr;
    if (XrResult r = findSession(handleOf(swapchain->session), session); r != XR_SUCCESS) return r;
    if (info != nullptr && info->type != XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO) return XR_ERROR_VALIDATION_FAILURE;
    if (swapchain->acquired.empty() || !swapchain->waited) return XR_ERROR_CALL_ORDER_INVALID;
    swapchain->lastReleased = swapchain->acquired.front();
    swapchain->acquired.pop_front();
    swapchain->waited = false;
    return XR_SUCCESS;
  });
}

}  // namespace xrsim
