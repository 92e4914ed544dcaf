// Glove HID reports from a device or a host (untrusted bytes): every decoder must reject bad
// input with a reason and never crash; whatever it accepts must re-encode to the same bytes.
#include <algorithm>
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
  Report third;
  encode(back, third);
  if (third != again) __builtin_trap();  // re-encoding is stable (input values are quantised once)
  if constexpr (!std::is_same_v<T, InputReport>) {
    if (!(back == value)) __builtin_trap();  // levels and device info are lossless
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
