// The driver's threads against the simulated glove over real report bytes, on the real clock:
// behaviour (what is sent, why output is silent, reconnection). The documented timing goals
// (silence within 50 ms, reports at 1 kHz) are asserted in simulated time, where load cannot
// bend them, in glove_timing_tests.cpp. Waits here are polls with generous bounds, never sleeps.
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <thread>

#include "glove_rig.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/stop.hpp"
#include "vt/haptics/devices/glove_driver.hpp"
#include "vt/haptics/devices/glove_setup.hpp"
#include "vt/haptics/devices/sim_transport.hpp"

using namespace vt::haptics;
using namespace vt::haptics::glove;
using namespace vt::haptics::glove::test;

namespace {

constexpr auto kGenerous = std::chrono::seconds(5);

template <class Pred>
bool waitFor(Pred pred, std::atomic<std::uint64_t>* beat = nullptr) {
  const auto end = std::chrono::steady_clock::now() + kGenerous;
  while (std::chrono::steady_clock::now() < end) {
    if (beat) beat->fetch_add(1);
    if (pred()) return true;
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  return pred();
}

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

struct Rig : SimRig {
  GloveDriverConfig config() {
    GloveDriverConfig c = SimRig::config();
    c.failsafe.stallTimeout_ns = 2'000'000'000;  // tests that are not about stalls must not trip it
    return c;
  }
};

}  // namespace

TEST_CASE("Glove driver drives the simulated glove and publishes its flexion") {
  Rig rig;
  rig.glove.setFlexion({0.1f, 0.3f, 0.5f, 0.7f, 0.9f});
  GloveDriver driver(rig.backend, rig.config());
  driver.submit(frameWith(0.5f, 1));
  REQUIRE(waitFor([&] { return std::abs(indexLevel(rig.glove) - 0.5f) < 1e-3f; }, &rig.beat));
  CHECK(rig.glove.levels()[std::size_t(ActuatorId::Thumb)] == 0.0f);
  vt::FingerCurls curls{};
  REQUIRE(waitFor([&] { return driver.flexion().read(curls); }));
  CHECK(curls[2] == Approx(0.5f).margin(1e-4));
  const GloveStatus status = driver.status();
  CHECK(status.connected);
  CHECK(status.path == SimGloveBackend::kPath);
  CHECK(std::string(status.info.serial.data()) == "SIM-0001");
  CHECK(status.connects == 1);
  CHECK(status.reportsSent >= 2);  // the silent report on connect, then the frame
  CHECK(status.inputRejected == 0);
  CHECK(rig.glove.stats().rejected() == 0);  // every byte the driver wrote was a valid report
}

TEST_CASE("Glove driver silences the glove when stopped") {
  Rig rig;
  auto driver = std::make_unique<GloveDriver>(rig.backend, rig.config());
  driver->submit(frameWith(1.0f, 1));
  REQUIRE(waitFor([&] { return indexLevel(rig.glove) == 1.0f; }, &rig.beat));
  driver.reset();  // destructor path
  CHECK(allZero(rig.glove));
  CHECK_FALSE(rig.glove.silenced());  // zeros were sent, not left to the keep-alive
}

TEST_CASE("Glove driver sends zeros on SIGINT") {
  Rig rig;
  vt::clearStop();
  vt::installStopSignals();
  GloveDriver driver(rig.backend, rig.config());
  driver.submit(frameWith(0.8f, 1));
  REQUIRE(waitFor([&] { return indexLevel(rig.glove) > 0.7f; }, &rig.beat));
  REQUIRE(std::raise(SIGINT) == 0);
  CHECK(waitFor([&] { return allZero(rig.glove); }, &rig.beat));
  CHECK_FALSE(rig.glove.silenced());
  CHECK(driver.status().failsafe == FailsafeReason::Signal);
  vt::clearStop();
  driver.submit(frameWith(0.8f, 2));
  CHECK(waitFor([&] { return indexLevel(rig.glove) > 0.7f; }, &rig.beat));
}

TEST_CASE("Glove driver watchdog silences a stalled haptic thread") {
  Rig rig;
  GloveDriverConfig config = rig.config();
  config.failsafe.stallTimeout_ns = 20'000'000;
  GloveDriver driver(rig.backend, config);
  driver.submit(frameWith(0.6f, 1));
  REQUIRE(waitFor([&] { return indexLevel(rig.glove) > 0.5f; }, &rig.beat));
  // The heartbeat stops moving: the last frame must not keep buzzing.
  CHECK(waitFor([&] { return allZero(rig.glove); }));
  CHECK(driver.status().failsafe == FailsafeReason::Stall);
  CHECK(waitFor([&] { return indexLevel(rig.glove) > 0.5f; }, &rig.beat));  // beats again: resumes
}

TEST_CASE("Glove driver network-loss hook silences until the link returns") {
  Rig rig;
  GloveDriver driver(rig.backend, rig.config());
  driver.submit(frameWith(0.6f, 1));
  REQUIRE(waitFor([&] { return indexLevel(rig.glove) > 0.5f; }, &rig.beat));
  driver.failsafe().setLinkLost(true);
  CHECK(waitFor([&] { return allZero(rig.glove); }, &rig.beat));
  CHECK(driver.status().failsafe == FailsafeReason::LinkLost);
  driver.failsafe().setLinkLost(false);
  CHECK(waitFor([&] { return indexLevel(rig.glove) > 0.5f; }, &rig.beat));
}

TEST_CASE("Glove driver reports a vanished device to the failsafe and clears it after a silent first report") {
  Rig rig;
  GloveDriver driver(rig.backend, rig.config());
  driver.submit(frameWith(0.6f, 1));
  REQUIRE(waitFor([&] { return indexLevel(rig.glove) > 0.5f; }, &rig.beat));
  CHECK_FALSE(driver.failsafe().linkLost());

  rig.backend.setPresent(false);  // the transport fails: the driver, not a test, tells the failsafe
  REQUIRE(waitFor([&] { return driver.failsafe().linkLost(); }, &rig.beat));
  CHECK(waitFor([&] { return driver.status().failsafe == FailsafeReason::LinkLost; }, &rig.beat));
  CHECK_FALSE(driver.status().connected);

  const std::uint64_t before = rig.glove.stats().accepted();
  rig.backend.setPresent(true);
  REQUIRE(waitFor([&] { return !driver.failsafe().linkLost(); }, &rig.beat));
  // The report that cleared it was silent: the glove saw zeros first, then the frame again.
  CHECK(rig.glove.stats().accepted() > before);
  CHECK(waitFor([&] { return indexLevel(rig.glove) > 0.5f; }, &rig.beat));
  CHECK(driver.status().failsafe == FailsafeReason::None);
}

TEST_CASE("Glove driver stays silent after a reconnect while the network link is still lost") {
  Rig rig;
  GloveDriver driver(rig.backend, rig.config());
  driver.submit(frameWith(0.6f, 1));
  REQUIRE(waitFor([&] { return indexLevel(rig.glove) > 0.5f; }, &rig.beat));
  driver.failsafe().setLinkLost(true);  // the network session's report
  REQUIRE(waitFor([&] { return allZero(rig.glove); }, &rig.beat));
  rig.backend.setPresent(false);
  REQUIRE(waitFor([&] { return !driver.status().connected; }, &rig.beat));
  rig.backend.setPresent(true);
  REQUIRE(waitFor([&] { return driver.status().connected && driver.status().connects == 2; }, &rig.beat));
  // The device link is back, the network link is not: output stays silent.
  REQUIRE(waitFor([&] { return driver.status().reportsSent > 0 && driver.status().failsafe == FailsafeReason::LinkLost; },
                  &rig.beat));
  CHECK(allZero(rig.glove));
  driver.failsafe().setLinkLost(false);
  CHECK(waitFor([&] { return indexLevel(rig.glove) > 0.5f; }, &rig.beat));
}

TEST_CASE("Glove driver reconnects after failing opens an unplug and write errors") {
  Rig rig;
  rig.backend.failNextOpens(2);
  GloveDriver driver(rig.backend, rig.config());
  driver.submit(frameWith(0.4f, 1));
  REQUIRE(waitFor([&] { return driver.status().connected; }, &rig.beat));
  CHECK(rig.backend.opens() == 1);

  rig.backend.setPresent(false);  // vanishes
  REQUIRE(waitFor([&] { return !driver.status().connected; }, &rig.beat));
  CHECK_FALSE(driver.status().lastError.empty());
  rig.backend.setPresent(true);  // returns
  REQUIRE(waitFor([&] { return driver.status().connected && driver.status().connects == 2; }, &rig.beat));
  driver.submit(frameWith(0.4f, 2));
  CHECK(waitFor([&] { return std::abs(indexLevel(rig.glove) - 0.4f) < 1e-3f; }, &rig.beat));

  const std::uint64_t errorsBefore = driver.status().writeErrors;  // the unplug counted too
  rig.backend.failWrites(true);  // I/O errors
  REQUIRE(waitFor([&] { return driver.status().writeErrors > errorsBefore; }, &rig.beat));
  rig.backend.failWrites(false);
  CHECK(waitFor([&] { return driver.status().connected && driver.status().connects >= 3; }, &rig.beat));
  CHECK(rig.glove.stats().rejected() == 0);
}

namespace {
// A device whose input reports are scripted byte strings, for the reader's rejection path.
class ScriptedDevice final : public HidDevice {
 public:
  explicit ScriptedDevice(std::vector<std::vector<std::uint8_t>> inputs) : m_inputs(std::move(inputs)) {}
  int write(std::span<const std::uint8_t> bytes) noexcept override { return int(bytes.size()); }
  int read(std::span<std::uint8_t> out, int timeout_ms) noexcept override {
    if (m_next >= m_inputs.size()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(timeout_ms));
      return 0;
    }
    const auto& in = m_inputs[m_next++];
    const std::size_t n = std::min(in.size(), out.size());
    std::copy_n(in.begin(), n, out.begin());
    return int(n);
  }
  int getFeature(std::span<std::uint8_t> out) noexcept override {
    Report info;
    encode(DeviceInfo::avatar("SCRIPTED"), info);
    std::copy(info.begin(), info.end(), out.begin());
    return int(info.size());
  }
  std::string lastError() const override { return "none"; }

 private:
  std::vector<std::vector<std::uint8_t>> m_inputs;
  std::size_t m_next = 0;
};

class ScriptedBackend final : public HidBackend {
 public:
  std::vector<std::vector<std::uint8_t>> inputs;
  std::vector<HidDeviceInfo> enumerate(std::uint16_t, std::uint16_t) override { return {{"scripted", 1, 2, "S", "", ""}}; }
  std::unique_ptr<HidDevice> open(const std::string&, std::string&) override {
    return std::make_unique<ScriptedDevice>(inputs);
  }
};
}  // namespace

TEST_CASE("Glove driver rejects and counts malformed input reports") {
  ScriptedBackend backend;
  InputReport good;
  good.flexion = {0.2f, 0.2f, 0.2f, 0.2f, 0.2f};
  Report goodBytes;
  encode(good, goodBytes);
  std::vector<std::uint8_t> valid(goodBytes.begin(), goodBytes.end());
  std::vector<std::uint8_t> shortOne(valid.begin(), valid.begin() + 10);
  std::vector<std::uint8_t> longOne = valid;
  longOne.push_back(0);
  std::vector<std::uint8_t> unknown = valid;
  unknown[0] = 0x55;
  backend.inputs = {shortOne, longOne, unknown, valid};
  GloveDriver driver(backend, GloveDriverConfig{});
  REQUIRE(waitFor([&] { return driver.status().inputReports == 1; }));
  CHECK(driver.status().inputRejected == 3);
  CHECK(driver.inputStats().count(ReportError::TooShort) == 1);
  CHECK(driver.inputStats().count(ReportError::TooLong) == 1);
  CHECK(driver.inputStats().count(ReportError::UnknownId) == 1);
  vt::FingerCurls curls{};
  REQUIRE(driver.flexion().read(curls));
  CHECK(curls[4] == Approx(0.2f).margin(1e-4));
}

TEST_CASE("Glove setup builds a simulated glove end to end and rejects unknown specs") {
  auto setup = GloveSetup::create("sim");
  REQUIRE(setup->simulated() != nullptr);
  setup->simulated()->setFlexion({0.0f, 0.9f, 0.0f, 0.0f, 0.0f});
  std::atomic<std::uint64_t> frames{0};
  ActuatorFrame frame = frameWith(0.3f, 1);
  // No heartbeat configured: fresh frames are the heartbeat, so keep publishing like a loop.
  REQUIRE(waitFor([&] {
    frame.sequence = frames.fetch_add(1);
    setup->driver().submit(frame);
    return std::abs(indexLevel(*setup->simulated()) - 0.3f) < 1e-3f;
  }));
  vt::FingerCurls curls{};
  REQUIRE(waitFor([&] { return setup->driver().flexion().read(curls) && curls[1] > 0.8f; }));
  CHECK_THROWS_WITH(GloveSetup::create("usb"), Catch::Contains("'usb'"));
  auto hid = GloveSetup::create("hid:NO-SUCH-SERIAL");
  CHECK(hid->simulated() == nullptr);
  CHECK_FALSE(hid->driver().status().connected);
}

TEST_CASE("Glove driver keeps up with a 1 kHz producer") {
  Rig rig;
  GloveDriver driver(rig.backend, rig.config());
  std::atomic<bool> run{true};
  // A stand-in haptic thread: a new frame and a heartbeat every millisecond.
  std::thread producer([&] {
    vt::SteadyClock clock;
    std::int64_t next = clock.now_ns();
    for (std::uint64_t i = 1; run.load(); ++i) {
      driver.submit(frameWith(float(i % 100) / 100.0f, i));
      rig.beat.fetch_add(1);
      next += 1'000'000;
      clock.sleepUntil(next);
    }
  });
  REQUIRE(waitFor([&] { return driver.status().connected; }));
  const auto start = std::chrono::steady_clock::now();
  REQUIRE(waitFor([&] { return driver.status().sendRate_hz > 0 && msSince(start) > 1100; }));
  run.store(false);
  producer.join();
  const GloveStatus status = driver.status();
  WARN("send rate " << status.sendRate_hz << " Hz, reports " << status.reportsSent << ", frames dropped "
                    << status.framesDropped);
  // The 1 kHz goal is asserted in simulated time (glove_timing_tests.cpp); on real time the rate
  // is the scheduler's (130 - 370 Hz at load 12 - 16 on the shared 2 cores). The bound is twice
  // the keep-alive rate (50 Hz), so a writer that only resent every 20 ms would fail it.
  CHECK(status.sendRate_hz > 100.0);
  // Every report sent arrived intact: counted once the writer has stopped (while it runs, a
  // report can land between reading the driver's count and the glove's; seen under TSan).
  driver.stop();
  CHECK(rig.glove.stats().accepted() == driver.status().reportsSent);
  CHECK(rig.glove.stats().rejected() == 0);
}
