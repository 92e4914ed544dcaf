#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "test_support.hpp"
#include "vt/haptics/devices/glove_protocol.hpp"

using namespace vt::haptics;
using namespace vt::haptics::glove;

namespace {

LevelsReport sampleLevels() {
  LevelsReport levels;
  levels.sequence = 0xBEEF;
  levels.actuatorCount = 10;
  levels.hasFrequency = true;
  for (std::size_t i = 0; i < 10; ++i) {
    levels.level[i] = std::uint16_t(1000 * i + 7);
    levels.frequency_hz[i] = std::uint16_t(100 + 25 * i);
  }
  return levels;
}

InputReport sampleInput() {
  InputReport input;
  input.sequence = 513;
  input.deviceTime_ms = 0x01020304;
  input.palmValid = true;
  input.charging = true;
  input.flexion = {0.0f, 0.25f, 0.5f, 0.75f, 1.0f};
  input.palm = glm::normalize(glm::quat(0.9f, 0.1f, -0.3f, 0.2f));
  input.contactPads = kPadIndex | kPadPalm;
  input.battery_percent = 64;
  return input;
}

// Re-seals a report after a field edit so only the field check can reject it.
void reseal(Report& r) {
  const std::uint16_t crc = crc16(std::span(r.data(), 62));
  r[62] = std::uint8_t(crc & 0xFF);
  r[63] = std::uint8_t(crc >> 8);
}

}  // namespace

TEST_CASE("Glove CRC-16 matches the CCITT-FALSE check value") {
  const char* text = "123456789";
  CHECK(crc16(std::span(reinterpret_cast<const std::uint8_t*>(text), 9)) == 0x29B1);
}

TEST_CASE("Device-info report round trips and has the documented byte layout") {
  DeviceInfo info = DeviceInfo::avatar("AVT-000042");
  info.maxUpdateRate_hz = 800;
  info.firmwareVersion = 0x0102;
  Report bytes;
  encode(info, bytes);
  CHECK(bytes[0] == kDeviceInfoReportId);
  CHECK(bytes[1] == 1);                      // protocol version
  CHECK(bytes[2] == 10);                     // actuator count
  CHECK(bytes[4 + 3] == std::uint8_t(ActuatorId::Ring));
  CHECK(bytes[14] == (800 & 0xFF));          // little-endian rate
  CHECK(bytes[15] == (800 >> 8));
  CHECK(std::memcmp(&bytes[20], "AVT-000042", 10) == 0);
  DeviceInfo back;
  REQUIRE(decode(bytes, back) == ReportError::None);
  CHECK(back == info);
  CHECK(std::string(back.serial.data()) == "AVT-000042");
}

TEST_CASE("Device-info report with a partial layout round trips") {
  DeviceInfo info;  // V-Touching preset: index, middle, ring only, no frequency control
  info.actuatorCount = 3;
  info.layout = {1, 2, 3, kNoActuator, kNoActuator, kNoActuator, kNoActuator, kNoActuator, kNoActuator, kNoActuator};
  info.maxUpdateRate_hz = 500;
  Report bytes;
  encode(info, bytes);
  DeviceInfo back;
  REQUIRE(decode(bytes, back) == ReportError::None);
  CHECK(back == info);
}

TEST_CASE("Levels report round trips with and without frequencies") {
  LevelsReport levels = sampleLevels();
  Report bytes;
  encode(levels, bytes);
  CHECK(bytes[0] == kLevelsReportId);
  CHECK(bytes[2] == 0xEF);  // sequence, little-endian
  CHECK(bytes[3] == 0xBE);
  CHECK(bytes[6 + 2] == (1007 & 0xFF));
  LevelsReport back;
  REQUIRE(decode(bytes, back) == ReportError::None);
  CHECK(back == levels);

  levels.hasFrequency = false;
  levels.frequency_hz = {};
  levels.actuatorCount = 4;
  for (std::size_t i = 4; i < 10; ++i) levels.level[i] = 0;
  encode(levels, bytes);
  REQUIRE(decode(bytes, back) == ReportError::None);
  CHECK(back == levels);
}

TEST_CASE("Input report round trips within quantisation") {
  const InputReport input = sampleInput();
  Report bytes;
  encode(input, bytes);
  InputReport back;
  REQUIRE(decode(bytes, back) == ReportError::None);
  CHECK(back.sequence == input.sequence);
  CHECK(back.deviceTime_ms == input.deviceTime_ms);
  CHECK(back.palmValid);
  CHECK(back.charging);
  CHECK_FALSE(back.silencedByKeepAlive);
  for (std::size_t i = 0; i < 5; ++i) CHECK(back.flexion[i] == Approx(input.flexion[i]).margin(1.0 / 65535));
  CHECK(std::abs(glm::dot(back.palm, input.palm)) == Approx(1.0).margin(1e-6));
  CHECK(back.contactPads == input.contactPads);
  CHECK(back.battery_percent == 64);
}

TEST_CASE("Frames map to device slots through the announced layout") {
  DeviceInfo info;
  info.actuatorCount = 3;
  info.capabilities = kCapFrequency;
  info.layout = {3, 1, 2, kNoActuator, kNoActuator, kNoActuator, kNoActuator, kNoActuator, kNoActuator, kNoActuator};
  ActuatorFrame frame;
  frame.actuatorCount = 5;
  frame.intensity = {0.9f, 0.5f, 1.0f, 0.25f, 0.7f};
  frame.frequency_hz = {0, 250, 180, 90.4f, 0};
  const LevelsReport levels = levelsFromFrame(frame, info, 7);
  CHECK(levels.actuatorCount == 3);
  CHECK(levels.sequence == 7);
  CHECK(levels.level[0] == 16384);  // ring, 0.25
  CHECK(levels.level[1] == 32768);  // index, 0.5
  CHECK(levels.level[2] == 65535);  // middle
  CHECK(levels.frequency_hz[0] == 90);
  CHECK(levels.level[3] == 0);

  frame.intensity[1] = std::numeric_limits<float>::quiet_NaN();  // never drive on garbage
  frame.intensity[2] = 7.0f;                                    // clamps
  const LevelsReport clamped = levelsFromFrame(frame, info, 8);
  CHECK(clamped.level[1] == 0);
  CHECK(clamped.level[2] == 65535);
  CHECK(silentLevels(info, 1).silent());
}

TEST_CASE("Short oversized and unknown-ID reports are rejected and counted") {
  Report good;
  encode(sampleLevels(), good);
  ReportStats stats;
  LevelsReport out;
  const auto check = [&](std::span<const std::uint8_t> bytes, ReportError expected) {
    const ReportError e = decode(bytes, out);
    stats.record(e);
    CHECK(e == expected);
  };
  check(std::span(good.data(), 0), ReportError::TooShort);
  check(std::span(good.data(), 63), ReportError::TooShort);
  std::vector<std::uint8_t> longer(good.begin(), good.end());
  longer.push_back(0);
  check(longer, ReportError::TooLong);
  Report unknown = good;
  unknown[0] = 0x7F;
  check(unknown, ReportError::UnknownId);
  Report input;
  encode(sampleInput(), input);
  check(input, ReportError::WrongId);
  check(good, ReportError::None);
  CHECK(stats.accepted() == 1);
  CHECK(stats.rejected() == 5);
  CHECK(stats.count(ReportError::TooShort) == 2);
  CHECK(reportErrorName(ReportError::UnknownId) == "unknown-id");
}

TEST_CASE("Inconsistent reports are rejected with a reason") {
  Report bytes;
  LevelsReport levels;
  InputReport input;
  DeviceInfo info;

  encode(sampleLevels(), bytes);
  bytes[10] ^= 0x01;
  CHECK(decode(bytes, levels) == ReportError::BadChecksum);

  encode(sampleLevels(), bytes);
  bytes[4] = 11;  // more actuators than the protocol knows
  reseal(bytes);
  CHECK(decode(bytes, levels) == ReportError::BadCount);

  LevelsReport partial = sampleLevels();
  partial.actuatorCount = 3;  // levels left in slots 3..9
  encode(partial, bytes);
  CHECK(decode(bytes, levels) == ReportError::BadValue);

  encode(sampleLevels(), bytes);
  bytes[1] |= 0x80;
  reseal(bytes);
  CHECK(decode(bytes, levels) == ReportError::ReservedBits);

  encode(sampleInput(), bytes);
  bytes[28] = 101;  // battery
  reseal(bytes);
  CHECK(decode(bytes, input) == ReportError::BadValue);

  encode(sampleInput(), bytes);
  bytes[18] = bytes[19] = 0;  // quaternion far from unit length
  bytes[20] = bytes[21] = 0;
  bytes[22] = bytes[23] = 0;
  bytes[24] = bytes[25] = 0;
  reseal(bytes);
  CHECK(decode(bytes, input) == ReportError::BadValue);

  encode(DeviceInfo::avatar("X"), bytes);
  bytes[1] = 2;
  reseal(bytes);
  CHECK(decode(bytes, info) == ReportError::UnsupportedVersion);

  encode(DeviceInfo::avatar("X"), bytes);
  bytes[5] = bytes[4];  // duplicate actuator id
  reseal(bytes);
  CHECK(decode(bytes, info) == ReportError::BadLayout);

  encode(DeviceInfo::avatar("X"), bytes);
  bytes[16] = 200;  // keep-alive longer than the protocol's 100 ms
  bytes[17] = 0;
  reseal(bytes);
  CHECK(decode(bytes, info) == ReportError::BadValue);

  encode(DeviceInfo::avatar("X"), bytes);
  bytes[21] = 0x07;  // control character in the serial
  reseal(bytes);
  CHECK(decode(bytes, info) == ReportError::BadValue);
}

TEST_CASE("Fuzz seed reports written independently from the protocol document decode") {
  // The seeds were produced by a separate script from docs/glove-protocol.md alone.
  const auto dir = vt::test::sourceDir() / "tests/fuzz/corpus/fuzz_glove_report";
  const auto load = [&](const char* name) {
    std::ifstream in(dir / name, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  LevelsReport levels;
  REQUIRE(decode(load("levels.bin"), levels) == ReportError::None);
  CHECK(levels.sequence == 7);
  CHECK(levels.hasFrequency);
  CHECK(levels.level[9] == 6553 * 9);
  CHECK(levels.frequency_hz[0] == 250);
  InputReport input;
  REQUIRE(decode(load("input.bin"), input) == ReportError::None);
  CHECK(input.deviceTime_ms == 123456);
  CHECK(input.flexion[4] == 1.0f);
  CHECK(input.contactPads == (kPadIndex | kPadPalm));
  CHECK(input.battery_percent == 77);
  DeviceInfo info;
  REQUIRE(decode(load("device_info.bin"), info) == ReportError::None);
  CHECK(std::string(info.serial.data()) == "AVT-0001");
  CHECK(info.firmwareVersion == 0x0100);
  CHECK(decode(load("levels_short.bin"), levels) == ReportError::TooShort);
  CHECK(decode(load("input_bad_crc.bin"), input) == ReportError::BadChecksum);
}

TEST_CASE("The worked example of the protocol document encodes byte for byte") {
  LevelsReport levels;
  levels.sequence = 7;
  levels.actuatorCount = 10;
  levels.level[1] = 0x8000;
  Report bytes;
  encode(levels, bytes);
  const std::uint8_t head[10] = {0x01, 0x00, 0x07, 0x00, 0x0A, 0x00, 0x00, 0x00, 0x00, 0x80};
  CHECK(std::equal(std::begin(head), std::end(head), bytes.begin()));
  CHECK(std::all_of(bytes.begin() + 10, bytes.begin() + 62, [](std::uint8_t b) { return b == 0; }));
  CHECK(bytes[62] == 0x13);
  CHECK(bytes[63] == 0xA0);
}
