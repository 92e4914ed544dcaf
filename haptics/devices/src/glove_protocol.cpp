#include "vt/haptics/devices/glove_protocol.hpp"

#include <algorithm>
#include <cmath>

namespace vt::haptics::glove {
namespace {

// Field offsets, one table per report (docs/glove-protocol.md is the reference).
constexpr std::size_t kCrcOffset = 62;
namespace levels_at {
constexpr std::size_t kFlags = 1, kSequence = 2, kCount = 4, kLevel = 6, kFrequency = 26;
}
namespace input_at {
constexpr std::size_t kFlags = 1, kSequence = 2, kTime = 4, kFlexion = 8, kQuat = 18, kPads = 26, kBattery = 28;
}
namespace info_at {
constexpr std::size_t kVersion = 1, kCount = 2, kCaps = 3, kLayout = 4, kRate = 14, kKeepAlive = 16,
                      kFirmware = 18, kSerial = 20;
}
constexpr std::uint8_t kLevelsFlagFrequency = 1u << 0;
constexpr std::uint8_t kInputFlagPalm = 1u << 0, kInputFlagSilenced = 1u << 1, kInputFlagCharging = 1u << 2;
constexpr std::uint16_t kAllPads = 0x3F;
constexpr std::uint8_t kAllCaps = 0x07;
constexpr float kQuatScale = 16384.0f;  // Q2.14

void put16(Report& r, std::size_t at, std::uint16_t v) noexcept {
  r[at] = std::uint8_t(v & 0xFF);
  r[at + 1] = std::uint8_t(v >> 8);
}
void put32(Report& r, std::size_t at, std::uint32_t v) noexcept {
  for (std::size_t i = 0; i < 4; ++i) r[at + i] = std::uint8_t(v >> (8 * i));
}
std::uint16_t get16(std::span<const std::uint8_t> b, std::size_t at) noexcept {
  return std::uint16_t(b[at] | (b[at + 1] << 8));
}
std::uint32_t get32(std::span<const std::uint8_t> b, std::size_t at) noexcept {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v |= std::uint32_t(b[at + i]) << (8 * i);
  return v;
}

std::uint16_t toUnit16(float value) noexcept {
  if (!(value > 0.0f)) return 0;  // also maps NaN to 0: never leave an actuator on by accident
  return std::uint16_t(std::lround(std::min(value, 1.0f) * 65535.0f));
}
std::int16_t toQ14(float value) noexcept {
  return std::int16_t(std::lround(std::clamp(value, -1.99f, 1.99f) * kQuatScale));
}

void seal(Report& r) noexcept { put16(r, kCrcOffset, crc16(std::span(r.data(), kCrcOffset))); }

// Size, ID and checksum checks shared by every decoder.
ReportError checkFrame(std::span<const std::uint8_t> b, std::uint8_t id) noexcept {
  if (b.size() < kReportSize) return ReportError::TooShort;
  if (b.size() > kReportSize) return ReportError::TooLong;
  if (b[0] != kLevelsReportId && b[0] != kInputReportId && b[0] != kDeviceInfoReportId) return ReportError::UnknownId;
  if (b[0] != id) return ReportError::WrongId;
  if (get16(b, kCrcOffset) != crc16(b.first(kCrcOffset))) return ReportError::BadChecksum;
  return ReportError::None;
}

}  // namespace

std::string_view reportErrorName(ReportError error) noexcept {
  static constexpr std::string_view kNames[kReportErrorCount] = {
      "none", "too-short", "too-long", "unknown-id", "wrong-id", "bad-checksum",
      "unsupported-version", "bad-count", "bad-layout", "bad-value", "reserved-bits"};
  const auto i = std::size_t(error);
  return i < std::size(kNames) ? kNames[i] : std::string_view("unknown");
}

std::uint16_t crc16(std::span<const std::uint8_t> bytes) noexcept {
  std::uint16_t crc = 0xFFFF;
  for (std::uint8_t byte : bytes) {
    crc ^= std::uint16_t(byte << 8);
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 0x8000) ? std::uint16_t((crc << 1) ^ 0x1021) : std::uint16_t(crc << 1);
  }
  return crc;
}

DeviceInfo DeviceInfo::avatar(std::string_view serial) noexcept {
  DeviceInfo info;
  info.actuatorCount = kMaxActuators;
  info.capabilities = kCapFrequency | kCapImu | kCapContactPads;
  for (int i = 0; i < kMaxActuators; ++i) info.layout[std::size_t(i)] = std::uint8_t(i);
  const std::size_t n = std::min(serial.size(), kSerialBytes);
  std::copy_n(serial.begin(), n, info.serial.begin());
  return info;
}

bool LevelsReport::silent() const noexcept {
  return std::all_of(level.begin(), level.end(), [](std::uint16_t v) { return v == 0; });
}

std::uint64_t ReportStats::rejected() const noexcept {
  std::uint64_t sum = 0;
  for (int i = 1; i < kReportErrorCount; ++i) sum += count(ReportError(i));
  return sum;
}

void encode(const DeviceInfo& info, Report& out) noexcept {
  out.fill(0);
  out[0] = kDeviceInfoReportId;
  out[info_at::kVersion] = info.protocolVersion;
  out[info_at::kCount] = info.actuatorCount;
  out[info_at::kCaps] = info.capabilities;
  std::copy(info.layout.begin(), info.layout.end(), out.begin() + info_at::kLayout);
  put16(out, info_at::kRate, info.maxUpdateRate_hz);
  put16(out, info_at::kKeepAlive, info.keepAliveTimeout_ms);
  put16(out, info_at::kFirmware, info.firmwareVersion);
  for (std::size_t i = 0; i < kSerialBytes && info.serial[i] != '\0'; ++i) out[info_at::kSerial + i] = std::uint8_t(info.serial[i]);
  seal(out);
}

void encode(const LevelsReport& levels, Report& out) noexcept {
  out.fill(0);
  out[0] = kLevelsReportId;
  out[levels_at::kFlags] = levels.hasFrequency ? kLevelsFlagFrequency : 0;
  put16(out, levels_at::kSequence, levels.sequence);
  out[levels_at::kCount] = levels.actuatorCount;
  for (std::size_t i = 0; i < kMaxActuators; ++i) {
    put16(out, levels_at::kLevel + 2 * i, levels.level[i]);
    if (levels.hasFrequency) put16(out, levels_at::kFrequency + 2 * i, levels.frequency_hz[i]);
  }
  seal(out);
}

void encode(const InputReport& input, Report& out) noexcept {
  out.fill(0);
  out[0] = kInputReportId;
  out[input_at::kFlags] = std::uint8_t((input.palmValid ? kInputFlagPalm : 0) |
                                       (input.silencedByKeepAlive ? kInputFlagSilenced : 0) |
                                       (input.charging ? kInputFlagCharging : 0));
  put16(out, input_at::kSequence, input.sequence);
  put32(out, input_at::kTime, input.deviceTime_ms);
  for (std::size_t i = 0; i < kFingerCount; ++i) put16(out, input_at::kFlexion + 2 * i, toUnit16(input.flexion[i]));
  if (input.palmValid) {
    const float q[4] = {input.palm.w, input.palm.x, input.palm.y, input.palm.z};
    for (std::size_t i = 0; i < 4; ++i) put16(out, input_at::kQuat + 2 * i, std::uint16_t(toQ14(q[i])));
  }
  put16(out, input_at::kPads, std::uint16_t(input.contactPads & kAllPads));
  out[input_at::kBattery] = input.battery_percent;
  seal(out);
}

ReportError decode(std::span<const std::uint8_t> b, DeviceInfo& out) noexcept {
  if (const ReportError e = checkFrame(b, kDeviceInfoReportId); e != ReportError::None) return e;
  DeviceInfo info;
  info.protocolVersion = b[info_at::kVersion];
  if (info.protocolVersion != kProtocolVersion) return ReportError::UnsupportedVersion;
  info.actuatorCount = b[info_at::kCount];
  if (info.actuatorCount == 0 || info.actuatorCount > kMaxActuators) return ReportError::BadCount;
  info.capabilities = b[info_at::kCaps];
  if (info.capabilities & ~kAllCaps) return ReportError::ReservedBits;
  std::uint32_t seen = 0;
  for (std::size_t i = 0; i < kMaxActuators; ++i) {
    const std::uint8_t id = b[info_at::kLayout + i];
    info.layout[i] = id;
    if (i >= info.actuatorCount) {
      if (id != kNoActuator) return ReportError::BadLayout;
      continue;
    }
    if (id >= kMaxActuators || (seen & (1u << id))) return ReportError::BadLayout;  // unknown or duplicate
    seen |= 1u << id;
  }
  info.maxUpdateRate_hz = get16(b, info_at::kRate);
  info.keepAliveTimeout_ms = get16(b, info_at::kKeepAlive);
  if (info.maxUpdateRate_hz == 0 || info.keepAliveTimeout_ms == 0 || info.keepAliveTimeout_ms > kKeepAliveTimeout_ms) {
    return ReportError::BadValue;
  }
  info.firmwareVersion = get16(b, info_at::kFirmware);
  bool ended = false;
  for (std::size_t i = 0; i < kSerialBytes; ++i) {
    const std::uint8_t c = b[info_at::kSerial + i];
    if (c == 0) {
      ended = true;
    } else if (ended || c < 0x20 || c > 0x7E) {
      return ReportError::BadValue;  // printable ASCII, NUL padded
    }
    info.serial[i] = ended ? '\0' : char(c);
  }
  out = info;
  return ReportError::None;
}

ReportError decode(std::span<const std::uint8_t> b, LevelsReport& out) noexcept {
  if (const ReportError e = checkFrame(b, kLevelsReportId); e != ReportError::None) return e;
  LevelsReport levels;
  const std::uint8_t flags = b[levels_at::kFlags];
  if (flags & ~kLevelsFlagFrequency) return ReportError::ReservedBits;
  levels.hasFrequency = flags & kLevelsFlagFrequency;
  levels.sequence = get16(b, levels_at::kSequence);
  levels.actuatorCount = b[levels_at::kCount];
  if (levels.actuatorCount > kMaxActuators) return ReportError::BadCount;
  for (std::size_t i = 0; i < kMaxActuators; ++i) {
    levels.level[i] = get16(b, levels_at::kLevel + 2 * i);
    levels.frequency_hz[i] = get16(b, levels_at::kFrequency + 2 * i);
    const bool unused = i >= levels.actuatorCount;
    // Slots past the count, and frequencies without the flag, must be zero.
    if ((unused && levels.level[i] != 0) || ((unused || !levels.hasFrequency) && levels.frequency_hz[i] != 0)) {
      return ReportError::BadValue;
    }
  }
  out = levels;
  return ReportError::None;
}

ReportError decode(std::span<const std::uint8_t> b, InputReport& out) noexcept {
  if (const ReportError e = checkFrame(b, kInputReportId); e != ReportError::None) return e;
  InputReport input;
  const std::uint8_t flags = b[input_at::kFlags];
  if (flags & ~(kInputFlagPalm | kInputFlagSilenced | kInputFlagCharging)) return ReportError::ReservedBits;
  input.palmValid = flags & kInputFlagPalm;
  input.silencedByKeepAlive = flags & kInputFlagSilenced;
  input.charging = flags & kInputFlagCharging;
  input.sequence = get16(b, input_at::kSequence);
  input.deviceTime_ms = get32(b, input_at::kTime);
  for (std::size_t i = 0; i < kFingerCount; ++i) input.flexion[i] = float(get16(b, input_at::kFlexion + 2 * i)) / 65535.0f;
  if (input.palmValid) {
    float q[4];
    for (std::size_t i = 0; i < 4; ++i) q[i] = float(std::int16_t(get16(b, input_at::kQuat + 2 * i))) / kQuatScale;
    const float norm2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    if (norm2 < 0.9f || norm2 > 1.1f) return ReportError::BadValue;  // not a rotation
    input.palm = glm::normalize(glm::quat(q[0], q[1], q[2], q[3]));
  }
  input.contactPads = get16(b, input_at::kPads);
  if (input.contactPads & ~kAllPads) return ReportError::ReservedBits;
  input.battery_percent = b[input_at::kBattery];
  if (input.battery_percent > 100 && input.battery_percent != kBatteryUnknown) return ReportError::BadValue;
  out = input;
  return ReportError::None;
}

LevelsReport levelsFromFrame(const ActuatorFrame& frame, const DeviceInfo& info, std::uint16_t sequence) noexcept {
  LevelsReport levels = silentLevels(info, sequence);
  levels.hasFrequency = info.capabilities & kCapFrequency;
  for (std::size_t slot = 0; slot < levels.actuatorCount; ++slot) {
    const std::uint8_t id = info.layout[slot];
    if (id >= frame.actuatorCount || id >= kMaxActuators) continue;  // actuator not driven by this frame
    levels.level[slot] = toUnit16(frame.intensity[id]);
    if (levels.hasFrequency) {
      const float f = frame.frequency_hz[id];
      levels.frequency_hz[slot] = f > 0.0f ? std::uint16_t(std::lround(std::min(f, 65535.0f))) : 0;
    }
  }
  return levels;
}

LevelsReport silentLevels(const DeviceInfo& info, std::uint16_t sequence) noexcept {
  LevelsReport levels;
  levels.sequence = sequence;
  levels.actuatorCount = std::min<std::uint8_t>(info.actuatorCount, kMaxActuators);
  return levels;
}

}  // namespace vt::haptics::glove
