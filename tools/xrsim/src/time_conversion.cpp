// XR_KHR_convert_timespec_time. xrsim's XrTime is std::chrono::steady_clock in nanoseconds,
// which on Linux is CLOCK_MONOTONIC, so the conversion is exact: apps stamp poses with the
// time they describe on their own monotonic clock.
#include "api.hpp"

namespace xrsim {
namespace {

XrResult checkInstance(XrInstance handle) {
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  return instance->timespecEnabled ? XR_SUCCESS : XR_ERROR_FUNCTION_UNSUPPORTED;
}

}  // namespace

XrResult XRAPI_CALL convertTimespecTimeToTime(XrInstance handle, const struct timespec* timespecTime, XrTime* time) {
  return guarded("xrConvertTimespecTimeToTimeKHR", [&]() -> XrResult {
    if (XrResult r = checkInstance(handle); r != XR_SUCCESS) return r;
    if (timespecTime == nullptr || time == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    const XrTime converted = XrTime(timespecTime->tv_sec) * 1'000'000'000 + XrTime(timespecTime->tv_nsec);
    if (converted <= 0) return XR_ERROR_TIME_INVALID;
    *time = converted;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL convertTimeToTimespecTime(XrInstance handle, XrTime time, struct timespec* timespecTime) {
  return guarded("xrConvertTimeToTimespecTimeKHR", [&]() -> XrResult {
    if (XrResult r = checkInstance(handle); r != XR_SUCCESS) return r;
    if (timespecTime == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (time <= 0) return XR_ERROR_TIME_INVALID;
    timespecTime->tv_sec = time_t(time / 1'000'000'000);
    timespecTime->tv_nsec = long(time % 1'000'000'000);
    return XR_SUCCESS;
  });
}

}  // namespace xrsim
