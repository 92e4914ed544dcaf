#include <catch2/catch.hpp>

#include "vt/core/clock.hpp"
#include "vt/haptics/devices/sim_glove.hpp"

using namespace vt::haptics;
using namespace vt::haptics::glove;

namespace {
Report levelsBytes(float level, std::uint16_t sequence) {
  LevelsReport levels = silentLevels(DeviceInfo::avatar(""), sequence);
  for (std::size_t i = 0; i < levels.actuatorCount; ++i) levels.level[i] = std::uint16_t(level * 65535.0f);
  Report bytes;
  encode(levels, bytes);
  return bytes;
}
}  // namespace

TEST_CASE("Simulated glove drives levels from the exact report bytes") {
  vt::ManualClock clock(1'000'000'000);
  SimulatedGlove glove(clock);
  CHECK(glove.silenced());  // nothing heard yet
  REQUIRE(glove.receiveOutput(levelsBytes(0.5f, 1)) == ReportError::None);
  CHECK_FALSE(glove.silenced());
  for (float level : glove.levels()) CHECK(level == Approx(0.5f).margin(1e-4));
  CHECK(glove.lastLevels().sequence == 1);
}

TEST_CASE("Simulated glove goes silent after the 100 ms keep-alive timeout") {
  vt::ManualClock clock(5'000'000'000);
  SimulatedGlove glove(clock);
  REQUIRE(glove.receiveOutput(levelsBytes(1.0f, 1)) == ReportError::None);
  clock.advance(99'000'000);
  CHECK(glove.levels()[std::size_t(ActuatorId::Index)] == 1.0f);
  clock.advance(1'000'000);  // exactly 100 ms since the last valid report
  CHECK(glove.silenced());
  for (float level : glove.levels()) CHECK(level == 0.0f);
  CHECK(glove.keepAliveTimeouts() == 1);
  Report input;
  glove.makeInputReport(input);
  InputReport decoded;
  REQUIRE(decode(input, decoded) == ReportError::None);
  CHECK(decoded.silencedByKeepAlive);

  // A fresh report revives it; an invalid one does not count as keep-alive.
  REQUIRE(glove.receiveOutput(levelsBytes(0.25f, 2)) == ReportError::None);
  CHECK_FALSE(glove.silenced());
  clock.advance(60'000'000);
  Report broken = levelsBytes(0.25f, 3);
  broken[62] ^= 0xFF;
  CHECK(glove.receiveOutput(broken) == ReportError::BadChecksum);
  clock.advance(40'000'000);
  CHECK(glove.silenced());
  CHECK(glove.keepAliveTimeouts() == 2);
  CHECK(glove.stats().count(ReportError::BadChecksum) == 1);
}

TEST_CASE("Simulated glove rejects reports for the wrong actuator count") {
  vt::ManualClock clock;
  SimGloveConfig config;
  config.info.actuatorCount = 3;
  config.info.layout = {3, 1, 2, kNoActuator, kNoActuator, kNoActuator, kNoActuator, kNoActuator, kNoActuator, kNoActuator};
  SimulatedGlove glove(clock, config);
  CHECK(glove.receiveOutput(levelsBytes(0.5f, 1)) == ReportError::BadCount);
  LevelsReport three = silentLevels(config.info, 2);
  three.level[0] = 65535;  // slot 0 = ring
  Report bytes;
  encode(three, bytes);
  REQUIRE(glove.receiveOutput(bytes) == ReportError::None);
  CHECK(glove.levels()[std::size_t(ActuatorId::Ring)] == 1.0f);
  CHECK(glove.levels()[std::size_t(ActuatorId::Thumb)] == 0.0f);
}

TEST_CASE("Simulated glove reports scripted flexion and its device info") {
  vt::ManualClock clock(2'000'000'000);
  SimulatedGlove glove(clock);
  glove.setFlexionScript([](std::int64_t t_ns) {
    const float x = float(t_ns % 1'000'000'000) / 1e9f;
    return vt::FingerCurls{x, x, x, x, x};
  });
  clock.advance(250'000'000);
  Report bytes;
  glove.makeInputReport(bytes);
  InputReport input;
  REQUIRE(decode(bytes, input) == ReportError::None);
  CHECK(input.flexion[1] == Approx(0.25f).margin(1e-4));
  CHECK(input.deviceTime_ms == 2250);
  CHECK(glove.flexion()[3] == Approx(0.25f).margin(1e-6));
  glove.setFlexion({0.5f, 0.4f, 0.3f, 0.2f, 0.1f});  // the UI sliders replace the script
  clock.advance(100'000'000);
  CHECK(glove.flexion()[0] == 0.5f);
  glove.makeInputReport(bytes);
  REQUIRE(decode(bytes, input) == ReportError::None);
  CHECK(input.flexion[4] == Approx(0.1f).margin(1e-4));

  std::array<std::uint8_t, kReportSize> feature{};
  feature[0] = kDeviceInfoReportId;
  REQUIRE(glove.readFeature(feature) == int(kReportSize));
  DeviceInfo info;
  REQUIRE(decode(feature, info) == ReportError::None);
  CHECK(info == glove.info());
  feature[0] = 0x42;
  CHECK(glove.readFeature(feature) == -1);
}
