#include "xr_check.hpp"

#include <openxr/openxr_reflection.h>

namespace vt::xr {

const char* resultName(XrResult result) noexcept {
  switch (result) {
#define VT_XR_RESULT_CASE(name, value) \
  case name:                           \
    return #name;
    XR_LIST_ENUM_XrResult(VT_XR_RESULT_CASE)
#undef VT_XR_RESULT_CASE
    default:
      return "unknown XrResult";
  }
}

XrCallError::XrCallError(const char* call, XrResult r)
    : Error(str("OpenXR: ", call, " failed: ", resultName(r), " (", int(r), ")")), result(r) {}

}  // namespace vt::xr
