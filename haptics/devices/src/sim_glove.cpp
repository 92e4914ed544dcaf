#include "vt/haptics/devices/sim_glove.hpp"

#include <algorithm>

namespace vt::haptics::glove {

SimulatedGlove::SimulatedGlove(const Clock& clock, SimGloveConfig config) : m_clock(clock), m_config(config) {
  m_levels = silentLevels(m_config.info, 0);
}

ReportError SimulatedGlove::receiveOutput(std::span<const std::uint8_t> bytes) {
  LevelsReport levels;
  ReportError error = decode(bytes, levels);
  // A report for a different actuator count than the device announced is inconsistent too.
  if (error == ReportError::None && levels.actuatorCount != m_config.info.actuatorCount) error = ReportError::BadCount;
  m_stats.record(error);
  if (error != ReportError::None) return error;
  const std::lock_guard lock(m_mutex);
  silencedLocked(m_clock.now_ns());  // account for a keep-alive expiry before this report
  m_levels = levels;
  m_everReceived = true;
  m_lastValid_ns = m_clock.now_ns();
  m_wasSilenced = false;
  return error;
}

int SimulatedGlove::readFeature(std::span<std::uint8_t> out) {
  if (out.empty() || out[0] != kDeviceInfoReportId) return -1;
  Report report;
  encode(m_config.info, report);
  const std::size_t n = std::min(out.size(), report.size());
  std::copy_n(report.begin(), n, out.begin());
  return int(n);
}

void SimulatedGlove::makeInputReport(Report& out) {
  const std::lock_guard lock(m_mutex);
  const std::int64_t now = m_clock.now_ns();
  InputReport input;
  input.sequence = m_inputSequence++;
  input.deviceTime_ms = std::uint32_t(now / 1'000'000);
  input.flexion = m_script ? m_script(now) : m_flexion;
  input.palmValid = true;  // the simulated palm stays level
  input.contactPads = m_pads;
  input.battery_percent = m_config.battery_percent;
  input.silencedByKeepAlive = silencedLocked(now);
  encode(input, out);
}

bool SimulatedGlove::silencedLocked(std::int64_t now_ns) const {
  const bool silenced = !m_everReceived || now_ns - m_lastValid_ns >= std::int64_t(m_config.info.keepAliveTimeout_ms) * 1'000'000;
  if (silenced && !m_wasSilenced) {
    m_wasSilenced = true;
    if (!m_levels.silent()) ++m_keepAliveTimeouts;
  }
  return silenced;
}

std::array<float, kMaxActuators> SimulatedGlove::levels() const {
  std::array<float, kMaxActuators> out{};
  const std::lock_guard lock(m_mutex);
  if (silencedLocked(m_clock.now_ns())) return out;
  for (std::size_t slot = 0; slot < m_levels.actuatorCount; ++slot) {
    const std::uint8_t id = m_config.info.layout[slot];
    if (id < kMaxActuators) out[id] = float(m_levels.level[slot]) / 65535.0f;
  }
  return out;
}

bool SimulatedGlove::silenced() const {
  const std::lock_guard lock(m_mutex);
  return silencedLocked(m_clock.now_ns());
}

std::uint64_t SimulatedGlove::keepAliveTimeouts() const {
  const std::lock_guard lock(m_mutex);
  silencedLocked(m_clock.now_ns());
  return m_keepAliveTimeouts;
}

LevelsReport SimulatedGlove::lastLevels() const {
  const std::lock_guard lock(m_mutex);
  return m_levels;
}

FingerCurls SimulatedGlove::flexion() const {
  const std::lock_guard lock(m_mutex);
  return m_script ? m_script(m_clock.now_ns()) : m_flexion;
}

void SimulatedGlove::setFlexion(const FingerCurls& flexion) {
  const std::lock_guard lock(m_mutex);
  m_flexion = flexion;
  m_script = nullptr;
}

void SimulatedGlove::setFlexionScript(FlexionScript script) {
  const std::lock_guard lock(m_mutex);
  m_script = std::move(script);
}

void SimulatedGlove::setContactPads(std::uint16_t pads) {
  const std::lock_guard lock(m_mutex);
  m_pads = pads;
}

}  // namespace vt::haptics::glove
