#pragma once
// OpenXR result checks that name the call (CHECK_XRCMD style), and result names.
#include <vulkan/vulkan.h>
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include "vt/core/error.hpp"

namespace vt::xr {

/// "XR_ERROR_RUNTIME_UNAVAILABLE" etc. (works without an instance).
const char* resultName(XrResult result) noexcept;

/// Thrown for a failed call; keeps the result so callers can tell loss from other failures.
class XrCallError : public Error {
 public:
  XrCallError(const char* call, XrResult result);
  XrResult result;
};

inline XrResult xrCheck(XrResult result, const char* call) {
  if (XR_FAILED(result)) throw XrCallError(call, result);
  return result;
}

/// True for the results that mean "restart": the session or instance is gone.
inline bool isLoss(XrResult r) noexcept { return r == XR_ERROR_SESSION_LOST || r == XR_ERROR_INSTANCE_LOST; }

}  // namespace vt::xr

#define VT_XR_CHECK(call) ::vt::xr::xrCheck((call), #call)
