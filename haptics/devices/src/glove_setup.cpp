#include "vt/haptics/devices/glove_setup.hpp"

#include "vt/core/error.hpp"
#include "vt/haptics/devices/sim_transport.hpp"

namespace vt::haptics::glove {

std::unique_ptr<GloveSetup> GloveSetup::create(std::string_view spec, GloveDriverConfig config) {
  std::unique_ptr<GloveSetup> setup(new GloveSetup());
  if (spec == "sim") {
    setup->m_sim = std::make_unique<SimulatedGlove>(SteadyClock::instance());
    setup->m_backend = std::make_unique<SimGloveBackend>(*setup->m_sim, config.vendorId, config.productId);
  } else if (spec == "hid" || spec.rfind("hid:", 0) == 0) {
    if (spec.size() > 4) {
      const std::string_view which = spec.substr(4);
      (which.front() == '/' ? config.path : config.serial) = std::string(which);
    }
    setup->m_backend = makeHidapiBackend();
  } else {
    fail("--glove: expected sim, hid, hid:SERIAL or hid:/dev/hidrawN, got '", spec, "'");
  }
  setup->m_driver = std::make_unique<GloveDriver>(*setup->m_backend, std::move(config));
  return setup;
}

GloveSetup::~GloveSetup() { m_driver.reset(); }

std::int64_t GloveSetup::latency_ns() const { return m_driver->reportPeriod_ns(); }

std::string GloveSetup::statusLine() const {
  const GloveStatus s = m_driver->status();
  std::string text = str(m_sim ? "simulated " : "hid ", s.connected ? "connected " : "not connected ", s.path,
                         s.connected ? str(" ", int(s.sendRate_hz), " reports/s") : std::string());
  if (s.failsafe != FailsafeReason::None) text += str(" failsafe: ", failsafeReasonName(s.failsafe));
  if (!s.connected && !s.lastError.empty()) text += " (" + s.lastError + ")";
  return text;
}

}  // namespace vt::haptics::glove
