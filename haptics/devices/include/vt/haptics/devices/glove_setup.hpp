#pragma once
// One object owning everything a `--glove` option asks for: the transport (hidapi or the
// in-process simulated glove) and the driver on top, so the app wires a single thing: a
// realtime actuator sink fed through the driver's mailbox.
#include <memory>
#include <string_view>

#include "vt/haptics/actuator_sink.hpp"
#include "vt/haptics/devices/glove_driver.hpp"
#include "vt/haptics/devices/sim_glove.hpp"

namespace vt::haptics::glove {

class GloveSetup final : public ActuatorSink {
 public:
  /// `spec`: "sim" (simulated glove), "hid" (first glove with config's VID/PID), "hid:SERIAL",
  /// or "hid:/dev/hidrawN" (a path). Throws vt::Error naming the spec when it is not one of those.
  /// Main thread; the driver's threads start at once.
  static std::unique_ptr<GloveSetup> create(std::string_view spec, GloveDriverConfig config = {});
  /// Stops the driver first (silent report), then releases the transport.
  ~GloveSetup() override;

  GloveDriver& driver() noexcept { return *m_driver; }
  /// The simulated device (for the UI's flexion sliders), nullptr for real gloves.
  SimulatedGlove* simulated() noexcept { return m_sim.get(); }
  /// ActuatorSink: the newest frame goes out as the next levels report, so it is felt up to one
  /// report period later.
  std::string name() const override { return m_sim ? "glove sim" : "glove hid"; }
  SinkThread thread() const override { return SinkThread::Realtime; }
  SinkPort port() override { return m_driver->mailbox(); }
  std::int64_t latency_ns() const override;
  std::string statusLine() const override;
  void stop() override { m_driver->stop(); }

 private:
  GloveSetup() = default;
  std::unique_ptr<SimulatedGlove> m_sim;
  std::unique_ptr<HidBackend> m_backend;
  std::unique_ptr<GloveDriver> m_driver;
};

}  // namespace vt::haptics::glove
