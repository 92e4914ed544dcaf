#pragma once
// The Avatar-style glove HID protocol (docs/glove-protocol.md): pure encode/decode of each
// report, kept apart from any transport. Every function here is noexcept, allocation-free and
// callable from any thread (the driver's device threads, the simulated glove, fuzzers).
#include <array>
#include <atomic>
#include <cstdint>
#include <span>
#include <string_view>

#include <glm/gtc/quaternion.hpp>

#include "vt/haptics/actuator_frame.hpp"
#include "vt/scene/hand.hpp"

namespace vt::haptics::glove {

/// Every report is exactly this many bytes, the report ID byte included (64-byte full-speed HID).
inline constexpr std::size_t kReportSize = 64;
inline constexpr std::uint8_t kProtocolVersion = 1;
/// Report IDs (first byte of every report).
inline constexpr std::uint8_t kLevelsReportId = 0x01;     // output, host -> device
inline constexpr std::uint8_t kInputReportId = 0x02;      // input, device -> host
inline constexpr std::uint8_t kDeviceInfoReportId = 0x03; // feature, host reads
/// Default USB ids: the pid.codes open-source VID with a test PID (configurable everywhere).
inline constexpr std::uint16_t kDefaultVendorId = 0x1209;
inline constexpr std::uint16_t kDefaultProductId = 0x0001;
/// A device silences every actuator when no valid levels report arrived for this long.
inline constexpr std::uint16_t kKeepAliveTimeout_ms = 100;
/// Layout slot value meaning "no actuator in this slot".
inline constexpr std::uint8_t kNoActuator = 0xFF;
inline constexpr std::size_t kSerialBytes = 32;
/// Contact-pad bits of the input report.
enum ContactPad : std::uint16_t {
  kPadThumb = 1u << 0, kPadIndex = 1u << 1, kPadMiddle = 1u << 2, kPadRing = 1u << 3,
  kPadLittle = 1u << 4, kPadPalm = 1u << 5,
};
/// Capability bits of the device-info report.
enum Capability : std::uint8_t { kCapFrequency = 1u << 0, kCapImu = 1u << 1, kCapContactPads = 1u << 2 };
/// Battery value meaning "no battery / unknown".
inline constexpr std::uint8_t kBatteryUnknown = 0xFF;

/// Why a report was rejected (None = accepted).
enum class ReportError : std::uint8_t {
  None = 0, TooShort, TooLong, UnknownId, WrongId, BadChecksum, UnsupportedVersion, BadCount,
  BadLayout, BadValue, ReservedBits,
};
inline constexpr int kReportErrorCount = 11;
/// Stable lower-case name of a rejection reason ("bad-checksum", ...).
std::string_view reportErrorName(ReportError error) noexcept;

/// Feature report 0x03: what the device is.
struct DeviceInfo {
  std::uint8_t protocolVersion = kProtocolVersion;
  std::uint8_t actuatorCount = 0;                // slots in use, 1..10
  std::uint8_t capabilities = 0;                 // Capability bits
  std::array<std::uint8_t, kMaxActuators> layout{};  // slot -> ActuatorId, kNoActuator past count
  std::uint16_t maxUpdateRate_hz = 1000;
  std::uint16_t keepAliveTimeout_ms = kKeepAliveTimeout_ms;
  std::uint16_t firmwareVersion = 0;
  std::array<char, kSerialBytes + 1> serial{};   // ASCII, NUL-terminated

  /// The full Avatar layout: slot i drives ActuatorId i, every capability.
  static DeviceInfo avatar(std::string_view serial) noexcept;
  bool operator==(const DeviceInfo&) const = default;
};

/// Output report 0x01: every actuator level at once (it is also the keep-alive).
struct LevelsReport {
  std::uint16_t sequence = 0;
  std::uint8_t actuatorCount = 0;  // slots in use (as in DeviceInfo)
  bool hasFrequency = false;       // frequency_hz fields meaningful
  std::array<std::uint16_t, kMaxActuators> level{};         // per slot, 0 = off, 65535 = full
  std::array<std::uint16_t, kMaxActuators> frequency_hz{};  // per slot, 0 = device default
  bool operator==(const LevelsReport&) const = default;
  /// True when every level is zero.
  bool silent() const noexcept;
};

/// Input report 0x02: hand state measured by the glove.
struct InputReport {
  std::uint16_t sequence = 0;
  std::uint32_t deviceTime_ms = 0;
  bool palmValid = false;
  bool silencedByKeepAlive = false;  // the device is holding actuators off (no recent levels)
  bool charging = false;
  FingerCurls flexion{};             // 0 = straight, 1 = fully curled, thumb first
  glm::quat palm{1, 0, 0, 0};        // palm orientation in the glove's own frame
  std::uint16_t contactPads = 0;     // ContactPad bits
  std::uint8_t battery_percent = kBatteryUnknown;  // 0..100 or kBatteryUnknown
};

using Report = std::array<std::uint8_t, kReportSize>;

/// CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF) as stored in bytes 62..63 of every report.
std::uint16_t crc16(std::span<const std::uint8_t> bytes) noexcept;

/// Encoders write all kReportSize bytes (reserved bytes zero, checksum filled in).
void encode(const DeviceInfo& info, Report& out) noexcept;
void encode(const LevelsReport& levels, Report& out) noexcept;
void encode(const InputReport& input, Report& out) noexcept;

/// Decoders accept exactly one well-formed report of their type; `out` is untouched on error.
ReportError decode(std::span<const std::uint8_t> bytes, DeviceInfo& out) noexcept;
ReportError decode(std::span<const std::uint8_t> bytes, LevelsReport& out) noexcept;
ReportError decode(std::span<const std::uint8_t> bytes, InputReport& out) noexcept;

/// Levels for one frame on a device with `info`'s layout: slot i gets actuator layout[i]'s
/// intensity (0..1 -> 0..65535); actuators the frame does not use get 0.
LevelsReport levelsFromFrame(const ActuatorFrame& frame, const DeviceInfo& info, std::uint16_t sequence) noexcept;
/// A report that silences every slot of `info`.
LevelsReport silentLevels(const DeviceInfo& info, std::uint16_t sequence) noexcept;

/// Accepted/rejected counters per reason; any thread may record and read.
class ReportStats {
 public:
  /// Counts one decode outcome.
  void record(ReportError error) noexcept { m_counts[std::size_t(error)].fetch_add(1, std::memory_order_relaxed); }
  /// Reports seen with this outcome.
  std::uint64_t count(ReportError error) const noexcept { return m_counts[std::size_t(error)].load(std::memory_order_relaxed); }
  /// Reports that decoded cleanly.
  std::uint64_t accepted() const noexcept { return count(ReportError::None); }
  /// Sum over every rejection reason.
  std::uint64_t rejected() const noexcept;

 private:
  std::array<std::atomic<std::uint64_t>, kReportErrorCount> m_counts{};
};

}  // namespace vt::haptics::glove
