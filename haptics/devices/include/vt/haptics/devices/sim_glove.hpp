#pragma once
// The device side of the glove protocol, in-process (`--glove sim`): it parses the exact
// output-report bytes a host writes, enforces the 100 ms keep-alive and produces input reports
// with scripted or UI-driven finger flexion. Thread-safe: every member may be called from any
// non-real-time thread (driver writer/reader threads, UI, tests).
#include <array>
#include <cstdint>
#include <functional>
#include <mutex>
#include <span>

#include "vt/core/clock.hpp"
#include "vt/haptics/devices/glove_protocol.hpp"

namespace vt::haptics::glove {

/// Finger flexion as a function of device time (scripted flexion).
using FlexionScript = std::function<FingerCurls(std::int64_t t_ns)>;

struct SimGloveConfig {
  DeviceInfo info = DeviceInfo::avatar("SIM-0001");
  std::uint8_t battery_percent = 87;
};

class SimulatedGlove {
 public:
  /// `clock` drives the keep-alive and the device timestamps (a ManualClock in tests).
  explicit SimulatedGlove(const Clock& clock, SimGloveConfig config = {});

  /// Host -> device: one output report as written on the wire; rejected reports are counted
  /// and change nothing (they do not feed the keep-alive either).
  ReportError receiveOutput(std::span<const std::uint8_t> bytes);
  /// Host reads a feature report: fills `out` (out[0] = requested ID); bytes, or -1 for unknown IDs.
  int readFeature(std::span<std::uint8_t> out);
  /// Device -> host: the next input report.
  void makeInputReport(Report& out);

  /// Current drive level 0..1 per ActuatorId (all zero while the keep-alive has expired).
  std::array<float, kMaxActuators> levels() const;
  /// True while no valid levels report arrived within the keep-alive timeout.
  bool silenced() const;
  /// Times the keep-alive silenced actuators that were on.
  std::uint64_t keepAliveTimeouts() const;
  /// The last accepted levels report (sequence, raw levels).
  LevelsReport lastLevels() const;
  const ReportStats& stats() const noexcept { return m_stats; }
  const DeviceInfo& info() const noexcept { return m_config.info; }

  /// The flexion the next input report will carry (the script's value now, if scripted).
  FingerCurls flexion() const;
  /// Fixed flexion (UI sliders); replaces any script.
  void setFlexion(const FingerCurls& flexion);
  /// Flexion from a script of device time; replaces any fixed value.
  void setFlexionScript(FlexionScript script);
  void setContactPads(std::uint16_t pads);

 private:
  bool silencedLocked(std::int64_t now_ns) const;

  const Clock& m_clock;
  SimGloveConfig m_config;
  ReportStats m_stats;
  mutable std::mutex m_mutex;
  LevelsReport m_levels;
  bool m_everReceived = false;
  std::int64_t m_lastValid_ns = 0;
  mutable bool m_wasSilenced = true;
  mutable std::uint64_t m_keepAliveTimeouts = 0;
  FingerCurls m_flexion{};
  FlexionScript m_script;
  std::uint16_t m_pads = 0;
  std::uint16_t m_inputSequence = 0;
};

}  // namespace vt::haptics::glove
