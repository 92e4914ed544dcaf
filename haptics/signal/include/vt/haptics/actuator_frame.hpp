#pragma once
// What the haptic loop produces each tick and every sink consumes (glove, XR controllers,
// recorder, network, UI). Trivially copyable: it moves through SPSC rings and mailboxes.
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace vt::haptics {

/// Actuator layout of an Avatar-style glove (ids are part of the glove protocol).
enum class ActuatorId : std::uint8_t {
  Thumb = 0, Index, Middle, Ring, Little,
  PalmIndexUp, PalmIndexDown, PalmMiddleUp, PalmLittleUp, PalmLittleDown,
};
inline constexpr int kMaxActuators = 10;
/// Largest waveform block per tick: 8 kHz output at a 250 Hz tick.
inline constexpr int kMaxBlockSamples = 32;

/// Human-readable actuator name ("index", "palm-little-down", ...); the fingers are named as
/// OpenXR's hand joints name them (thumb, index, middle, ring, little) everywhere.
std::string_view actuatorName(ActuatorId id) noexcept;
/// The name files, channel maps and OSC paths used before the finger names were unified
/// ("pinky", "palm-pinky-up", "palm-pinky-down"); the current name for the other actuators.
std::string_view legacyActuatorName(ActuatorId id) noexcept;
/// The actuator a current or legacy name means; nullopt for any other text.
std::optional<ActuatorId> actuatorFromName(std::string_view name) noexcept;

/// One tick of tactile output for every actuator.
struct ActuatorFrame {
  std::uint64_t sequence = 0;
  std::int64_t t_ns = 0;           // when the haptic loop produced the frame (SteadyClock)
  std::int64_t pose_t_ns = 0;      // stamp of the newest hand pose the history held then
  std::int64_t hand_t_ns = 0;      // the time the hand was sampled for (the moment it renders)
  std::uint8_t actuatorCount = 0;  // actuators in use, ids 0..actuatorCount-1
  std::uint16_t blockLength = 0;   // waveform samples per actuator in this frame
  std::uint32_t sampleRate_hz = 0; // of the waveform block
  std::array<float, kMaxActuators> intensity{};     // 0..1, drive level for level-based devices
  std::array<float, kMaxActuators> frequency_hz{};  // dominant frequency, 0 = unknown
  std::array<std::array<float, kMaxBlockSamples>, kMaxActuators> block{};  // -1..1 waveform

  /// A frame that drives every actuator to zero (the failsafe's output).
  static ActuatorFrame silent(std::uint8_t actuatorCount, std::int64_t t_ns) noexcept {
    ActuatorFrame frame;
    frame.actuatorCount = actuatorCount;
    frame.t_ns = t_ns;
    return frame;
  }
};

}  // namespace vt::haptics
