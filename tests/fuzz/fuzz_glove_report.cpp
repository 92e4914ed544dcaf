// Glove HID reports from a device or a host (untrusted bytes): every decoder must reject bad
// input with a reason and never crash; whatever it accepts must re-encode to the same bytes.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <type_traits>

#include "vt/haptics/devices/glove_protocol.hpp"

namespace {
using namespace vt::haptics::glove;

template <class T>
void roundTrip(std::span<const std::uint8_t> bytes) {
  T value;
  const ReportError error = decode(bytes, value);
  if (reportErrorName(error) == "unknown") __builtin_trap();
  if (error != ReportError::None) return;
  Report again;
  encode(value, again);
  T back;
  if (decode(again, back) != ReportError::None) __builtin_trap();
  if constexpr (std::is_same_v<T, InputReport>) {
    // Quantised fields survive exactly; the palm quaternion is renormalised, so up to rounding.
    if (back.sequence != value.sequence || back.deviceTime_ms != value.deviceTime_ms || back.flexion != value.flexion ||
        back.contactPads != value.contactPads || back.battery_percent != value.battery_percent ||
        back.palmValid != value.palmValid || back.silencedByKeepAlive != value.silencedByKeepAlive ||
        back.charging != value.charging || std::abs(glm::dot(back.palm, value.palm)) < 1.0f - 1e-4f) {
      __builtin_trap();
    }
  } else if (!(back == value)) {
    __builtin_trap();  // levels and device info are lossless
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  roundTrip<LevelsReport>(bytes);
  roundTrip<InputReport>(bytes);
  roundTrip<DeviceInfo>(bytes);
  // Fuzzers rarely find a valid CRC: also try the same bytes with the checksum repaired.
  if (size == kReportSize) {
    Report sealed;
    std::copy_n(data, kReportSize, sealed.begin());
    const std::uint16_t crc = crc16(std::span(sealed.data(), 62));
    sealed[62] = std::uint8_t(crc & 0xFF);
    sealed[63] = std::uint8_t(crc >> 8);
    roundTrip<LevelsReport>(sealed);
    roundTrip<InputReport>(sealed);
    roundTrip<DeviceInfo>(sealed);
  }
  return 0;
}
