#pragma once
// Host side of the glove protocol: a writer thread sends the newest ActuatorFrame as a levels
// report at up to 1 kHz (the haptic thread only publishes into a mailbox and never blocks),
// a reader thread decodes input reports and publishes finger flexion, and the connection is
// re-established by itself after an unplug or an I/O error. Every failsafe path ends in a
// silent report: shutdown, SIGINT/SIGTERM, a stalled heartbeat, a lost network link, and a lost
// device link (reported to the failsafe as Link::Device from the start until the first report of
// each (re)connection, which is therefore silent).
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "vt/core/clock.hpp"
#include "vt/core/latest_value.hpp"
#include "vt/haptics/devices/failsafe.hpp"
#include "vt/haptics/devices/glove_protocol.hpp"
#include "vt/haptics/devices/hid_transport.hpp"

namespace vt::haptics::glove {

struct GloveDriverConfig {
  std::uint16_t vendorId = kDefaultVendorId;
  std::uint16_t productId = kDefaultProductId;
  std::string path;    // open exactly this device path (empty: by serial, else the first match)
  std::string serial;  // open the device with this serial (empty: any)
  int maxRate_hz = 1000;                          // capped by the device's own maximum
  std::int64_t keepAlivePeriod_ns = 20'000'000;   // resend unchanged levels this often (device: 100 ms)
  std::int64_t reconnectInterval_ns = 200'000'000;
  int readTimeout_ms = 20;
  FailsafeConfig failsafe;
  /// The haptic loop's tick counter (must outlive the driver); nullptr: new frames are the heartbeat.
  const std::atomic<std::uint64_t>* heartbeat = nullptr;
};

/// A snapshot for the UI.
struct GloveStatus {
  bool connected = false;
  std::string path;
  DeviceInfo info;
  double sendRate_hz = 0;            // levels reports per second over the last second
  std::uint64_t reportsSent = 0;
  std::uint64_t framesDropped = 0;   // frames overwritten in the mailbox before the writer took them
  std::uint64_t writeErrors = 0;
  std::uint64_t connects = 0;        // successful (re)connections
  std::uint64_t inputReports = 0;    // accepted input reports
  std::uint64_t inputRejected = 0;   // malformed input reports (any reason)
  FailsafeReason failsafe = FailsafeReason::None;
  std::string lastError;             // empty when nothing went wrong yet
};

class GloveDriver {
 public:
  /// Starts the device threads at once; `backend` and `clock` must outlive the driver. Main thread.
  GloveDriver(HidBackend& backend, GloveDriverConfig config, const Clock& clock = SteadyClock::instance());
  /// Same as stop().
  ~GloveDriver();
  GloveDriver(const GloveDriver&) = delete;
  GloveDriver& operator=(const GloveDriver&) = delete;

  /// Haptic thread: hands over the newest frame. Lock-free, never blocks.
  void submit(const ActuatorFrame& frame) noexcept { m_frames.publish(frame); }
  /// The frame mailbox itself, for a producer that publishes directly (one producer only).
  LatestValue<ActuatorFrame>& mailbox() noexcept { return m_frames; }
  /// Any thread: the newest finger flexion / full input report measured by the glove.
  const LatestValue<FingerCurls>& flexion() const noexcept { return m_flexion; }
  const LatestValue<InputReport>& input() const noexcept { return m_input; }
  /// The failsafe the writer obeys (network hook: failsafe().setLinkLost(true)); the driver
  /// itself reports the device's link (Link::Device). Any thread.
  Failsafe& failsafe() noexcept { return m_failsafe; }
  /// Rejected input reports by reason. Any thread.
  const ReportStats& inputStats() const noexcept { return m_inputStats; }
  /// UI thread (any non-real-time thread).
  GloveStatus status() const;
  /// The period of levels reports: the configured rate capped by the connected device's own
  /// maximum (the configured rate while none is connected). Any non-real-time thread.
  std::int64_t reportPeriod_ns() const;
  /// Sends a silent report (when connected) and joins the threads. Idempotent. Main thread.
  void stop();

 private:
  void writerLoop();
  void readerLoop();
  bool connect();
  void disconnect(const std::string& why);
  bool send(const LevelsReport& levels);
  void setError(const std::string& error);
  std::uint64_t heartbeat() const noexcept;

  HidBackend& m_backend;
  const GloveDriverConfig m_config;
  const Clock& m_clock;
  Failsafe m_failsafe;
  LatestValue<ActuatorFrame> m_frames;
  LatestValue<FingerCurls> m_flexion;
  LatestValue<InputReport> m_input;
  ReportStats m_inputStats;

  mutable std::mutex m_mutex;  // guards the fields below up to m_lastError
  std::shared_ptr<HidDevice> m_device;
  std::uint64_t m_generation = 0;  // bumped per connection
  std::string m_path;
  DeviceInfo m_info;
  std::string m_lastError;

  std::atomic<bool> m_connected{false};
  std::atomic<std::uint64_t> m_readFailedGeneration{0};
  std::atomic<double> m_sendRate_hz{0};
  std::atomic<std::uint64_t> m_reportsSent{0}, m_framesDropped{0}, m_writeErrors{0}, m_connects{0};
  std::atomic<bool> m_stopping{false};
  std::atomic<bool> m_readerStop{false};
  // Writer-thread state.
  std::uint16_t m_sequence = 0;
  std::thread m_writer;
  std::thread m_reader;
};

}  // namespace vt::haptics::glove
