#include "vt/haptics/devices/glove_driver.hpp"

#include <algorithm>
#include <iomanip>

#include "vt/core/error.hpp"
#include "vt/core/log.hpp"

namespace vt::haptics::glove {
namespace {

constexpr std::int64_t kIdleTick_ns = 5'000'000;  // writer tick while disconnected
constexpr std::int64_t kRateWindow_ns = 1'000'000'000;

bool sameOutput(const LevelsReport& a, const LevelsReport& b) noexcept {
  return a.actuatorCount == b.actuatorCount && a.hasFrequency == b.hasFrequency && a.level == b.level &&
         a.frequency_hz == b.frequency_hz;
}

std::string hex4(std::uint16_t v) { return str(std::hex, std::setw(4), std::setfill('0'), v); }

}  // namespace

GloveDriver::GloveDriver(HidBackend& backend, GloveDriverConfig config, const Clock& clock)
    : m_backend(backend), m_config(std::move(config)), m_clock(clock), m_failsafe(clock, m_config.failsafe) {
  if (m_config.maxRate_hz <= 0) fail("glove driver: maxRate_hz must be positive, got ", m_config.maxRate_hz);
  m_failsafe.setLinkLost(true, Link::Device);  // no device yet
  m_writer = std::thread([this] { writerLoop(); });
  m_reader = std::thread([this] { readerLoop(); });
}

GloveDriver::~GloveDriver() { stop(); }

void GloveDriver::stop() {
  m_failsafe.requestShutdown();
  m_stopping.store(true);
  if (m_writer.joinable()) m_writer.join();  // its last act is the silent report
  m_readerStop.store(true);
  if (m_reader.joinable()) m_reader.join();
  const std::lock_guard lock(m_mutex);
  m_device.reset();
  m_connected.store(false);
}

GloveStatus GloveDriver::status() const {
  GloveStatus s;
  {
    const std::lock_guard lock(m_mutex);
    s.path = m_path;
    s.info = m_info;
    s.lastError = m_lastError;
  }
  s.connected = m_connected.load();
  s.sendRate_hz = m_sendRate_hz.load();
  s.reportsSent = m_reportsSent.load();
  s.framesDropped = m_framesDropped.load();
  s.writeErrors = m_writeErrors.load();
  s.connects = m_connects.load();
  s.inputReports = m_inputStats.accepted();
  s.inputRejected = m_inputStats.rejected();
  s.failsafe = m_failsafe.lastReason();
  return s;
}

std::int64_t GloveDriver::reportPeriod_ns() const {
  int rate_hz = m_config.maxRate_hz;
  if (m_connected.load()) {
    const std::lock_guard lock(m_mutex);
    rate_hz = std::min<int>(rate_hz, std::max<int>(m_info.maxUpdateRate_hz, 1));
  }
  return 1'000'000'000 / rate_hz;
}

void GloveDriver::setError(const std::string& error) {
  bool changed = false;
  {
    const std::lock_guard lock(m_mutex);
    changed = error != m_lastError;
    m_lastError = error;
  }
  if (changed) log::warn("glove: ", error);  // once per distinct error, not once per retry
}

bool GloveDriver::connect() {
  const auto devices = m_backend.enumerate(m_config.vendorId, m_config.productId);
  const HidDeviceInfo* chosen = nullptr;
  for (const auto& d : devices) {
    if (!m_config.path.empty() ? d.path == m_config.path : (m_config.serial.empty() || d.serial == m_config.serial)) {
      chosen = &d;
      break;
    }
  }
  if (!chosen) {
    setError(str("no glove ", hex4(m_config.vendorId), ":", hex4(m_config.productId),
                 m_config.path.empty() ? "" : " at path " + m_config.path,
                 m_config.serial.empty() ? "" : " with serial " + m_config.serial, " found"));
    return false;
  }
  std::string error;
  std::shared_ptr<HidDevice> device = m_backend.open(chosen->path, error);
  if (!device) {
    setError(error);
    return false;
  }
  std::array<std::uint8_t, kReportSize + 1> feature{};  // one spare byte exposes oversized replies
  feature[0] = kDeviceInfoReportId;
  const int n = device->getFeature(feature);
  if (n < 0) {
    setError(str(chosen->path, ": reading device-info feature report failed: ", device->lastError()));
    return false;
  }
  DeviceInfo info;
  if (const ReportError e = decode(std::span(feature.data(), std::size_t(n)), info); e != ReportError::None) {
    setError(str(chosen->path, ": device-info report rejected (", reportErrorName(e), ")"));
    return false;
  }
  {
    const std::lock_guard lock(m_mutex);
    m_device = std::move(device);
    ++m_generation;
    m_path = chosen->path;
    m_info = info;
    m_lastError.clear();
  }
  m_connects.fetch_add(1);
  m_connected.store(true);
  log::info("glove: connected ", chosen->path, " serial ", info.serial.data(), ", ", int(info.actuatorCount),
            " actuators, up to ", info.maxUpdateRate_hz, " Hz");
  return true;
}

std::uint64_t GloveDriver::heartbeat() const noexcept {
  return m_config.heartbeat ? m_config.heartbeat->load(std::memory_order_relaxed) : m_frames.version();
}

void GloveDriver::disconnect(const std::string& why) {
  m_failsafe.setLinkLost(true, Link::Device);
  setError(why);
  const std::lock_guard lock(m_mutex);
  m_device.reset();  // the reader drops its own reference after its current read
  m_connected.store(false);
}

bool GloveDriver::send(const LevelsReport& levels) {
  std::shared_ptr<HidDevice> device;
  {
    const std::lock_guard lock(m_mutex);
    device = m_device;
  }
  if (!device) return false;
  Report report;
  encode(levels, report);
  if (device->write(report) != int(report.size())) {
    m_writeErrors.fetch_add(1);
    disconnect(str(m_path, ": write failed: ", device->lastError()));
    return false;
  }
  m_reportsSent.fetch_add(1);
  return true;
}

void GloveDriver::writerLoop() {
  std::uint64_t seenVersion = 0;  // mailbox version of `frame`; 0 = no frame yet
  std::uint64_t readFailedSeen = 0;
  ActuatorFrame frame;
  LevelsReport lastSent;
  std::int64_t lastSent_ns = 0;
  std::int64_t nextConnect_ns = m_clock.now_ns();
  bool justConnected = false;
  std::int64_t windowStart_ns = m_clock.now_ns();
  std::uint64_t windowStartCount = m_reportsSent.load();
  std::int64_t next_ns = m_clock.now_ns();

  while (true) {
    const bool stopping = m_stopping.load();
    std::int64_t now = m_clock.now_ns();
    if (!m_connected.load()) {
      // Nothing to silence without a device (its keep-alive holds it quiet), but the failsafe's
      // answer (link lost) stays current for status().
      if (stopping) break;
      m_failsafe.evaluate(heartbeat());
      justConnected = false;
      if (now >= nextConnect_ns) {
        nextConnect_ns = now + m_config.reconnectInterval_ns;
        justConnected = connect();
      }
      if (!justConnected) {
        m_clock.sleepUntil(now + std::min(kIdleTick_ns, m_config.reconnectInterval_ns));
        continue;
      }
      now = m_clock.now_ns();
      next_ns = now;
    }
    if (const std::uint64_t failed = m_readFailedGeneration.load(); failed != readFailedSeen) {
      readFailedSeen = failed;
      if (failed == m_generation) {  // m_generation only changes on this thread
        disconnect(str(m_path, ": input read failed, reconnecting"));
        continue;
      }
    }

    const std::uint64_t version = m_frames.version();
    if (version != seenVersion && m_frames.read(frame)) {
      m_framesDropped.fetch_add(version - seenVersion - 1);
      seenVersion = version;
    }
    // The first report of every (re)connection is silent, whatever state the device was left in:
    // the device link counts as lost until that report is out.
    const FailsafeReason reason = m_failsafe.evaluate(heartbeat());
    const bool drive = reason == FailsafeReason::None && seenVersion > 0;
    const LevelsReport levels = drive ? levelsFromFrame(frame, m_info, m_sequence) : silentLevels(m_info, m_sequence);
    // Resend unchanged levels well inside the device's keep-alive timeout.
    const std::int64_t keepAlive_ns = std::min(m_config.keepAlivePeriod_ns, std::int64_t(m_info.keepAliveTimeout_ms) * 250'000);
    if (justConnected || stopping || !sameOutput(levels, lastSent) || now - lastSent_ns >= keepAlive_ns) {
      if (send(levels)) {
        lastSent = levels;
        lastSent_ns = now;
        ++m_sequence;
        if (justConnected) m_failsafe.setLinkLost(false, Link::Device);
        justConnected = false;
      }
    }
    if (stopping) break;

    if (now - windowStart_ns >= kRateWindow_ns) {
      const std::uint64_t sent = m_reportsSent.load();
      m_sendRate_hz.store(double(sent - windowStartCount) * 1e9 / double(now - windowStart_ns));
      windowStart_ns = now;
      windowStartCount = sent;
    }
    const int rate_hz = std::min<int>(m_config.maxRate_hz, std::max<int>(m_info.maxUpdateRate_hz, 1));
    const std::int64_t period_ns = 1'000'000'000 / rate_hz;
    next_ns = std::max(next_ns + period_ns, now);  // after a hiccup, do not burst to catch up
    m_clock.sleepUntil(next_ns);
  }
}

void GloveDriver::readerLoop() {
  std::array<std::uint8_t, kReportSize + 1> buffer{};  // one spare byte exposes oversized reports
  std::uint64_t failedGeneration = 0;
  while (!m_readerStop.load()) {
    std::shared_ptr<HidDevice> device;
    std::uint64_t generation = 0;
    {
      const std::lock_guard lock(m_mutex);
      device = m_device;
      generation = m_generation;
    }
    if (!device || generation == failedGeneration) {
      m_clock.sleepUntil(m_clock.now_ns() + kIdleTick_ns);
      continue;
    }
    const int n = device->read(buffer, m_config.readTimeout_ms);
    if (n < 0) {
      failedGeneration = generation;
      setError(str("input read failed: ", device->lastError()));
      m_readFailedGeneration.store(generation);
      continue;
    }
    if (n == 0) continue;
    InputReport input;
    const ReportError error = decode(std::span(buffer.data(), std::size_t(n)), input);
    m_inputStats.record(error);
    if (error != ReportError::None) continue;
    m_input.publish(input);
    m_flexion.publish(input.flexion);
  }
}

}  // namespace vt::haptics::glove
