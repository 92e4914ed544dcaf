#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

#include "test_support.hpp"
#include "vt/haptics/devices/recorder.hpp"

using namespace vt::haptics;

namespace {
std::vector<std::uint8_t> readAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
std::uint32_t le(const std::vector<std::uint8_t>& b, std::size_t at, int bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= std::uint32_t(b[at + std::size_t(i)]) << (8 * i);
  return v;
}
}  // namespace

TEST_CASE("Recorder writes per-actuator CSV rows and a WAV channel per actuator") {
  const auto dir = vt::test::outputDir("glove_recorder");
  vt::SpscRing<ActuatorFrame> ring(8);
  for (int f = 0; f < 3; ++f) {
    ActuatorFrame frame;
    frame.sequence = std::uint64_t(f);
    frame.t_ns = 1'000'000 * f;
    frame.actuatorCount = 10;
    frame.blockLength = 8;
    frame.sampleRate_hz = 8000;
    frame.intensity[2] = 0.5f;
    frame.frequency_hz[2] = 250.0f;
    for (int s = 0; s < 8; ++s) frame.block[2][std::size_t(s)] = (s % 2) ? 0.5f : -1.0f;
    REQUIRE(ring.push(frame));
  }
  {
    ActuatorRecorder recorder(dir / "signals.csv", dir / "signals.wav");
    CHECK(recorder.drain(ring) == 3);
    ActuatorFrame odd;  // different sample rate: CSV only
    odd.actuatorCount = 10;
    odd.blockLength = 4;
    odd.sampleRate_hz = 4000;
    recorder.record(odd);
    CHECK_FALSE(std::filesystem::exists(dir / "signals.csv"));  // whole files appear at finish()
    CHECK_FALSE(std::filesystem::exists(dir / "signals.wav"));
    recorder.finish();
    CHECK(recorder.frames() == 4);
    CHECK(recorder.wavSamples() == 24);
    CHECK(recorder.rateMismatches() == 1);
  }

  std::ifstream csv(dir / "signals.csv");
  std::string header, row;
  std::getline(csv, header);
  CHECK(header.rfind("t_ns,sequence,thumb,index,middle,", 0) == 0);
  CHECK(header.find(",little,palm-index-up,") != std::string::npos);
  CHECK(header.find("palm-little-down_hz") != std::string::npos);
  CHECK(header.find("pinky") == std::string::npos);
  std::getline(csv, row);
  CHECK(row.rfind("0,0,0,0,0.5,", 0) == 0);
  int rows = 1;
  while (std::getline(csv, row)) ++rows;
  CHECK(rows == 4);

  const auto wav = readAll(dir / "signals.wav");
  REQUIRE(wav.size() == 44 + 24 * 10 * 2);
  CHECK(std::string(wav.begin(), wav.begin() + 4) == "RIFF");
  CHECK(le(wav, 22, 2) == 10);    // channels
  CHECK(le(wav, 24, 4) == 8000);  // sample rate
  CHECK(le(wav, 34, 2) == 16);    // bits
  CHECK(le(wav, 40, 4) == 24 * 10 * 2);
  // Sample 0, channel 2 (middle) is -1.0 -> -32767; sample 1 is 0.5 -> 16384.
  CHECK(std::int16_t(le(wav, 44 + 2 * 2, 2)) == -32767);
  CHECK(std::int16_t(le(wav, 44 + 20 + 2 * 2, 2)) == 16384);
  CHECK(std::int16_t(le(wav, 44 + 0, 2)) == 0);
}

TEST_CASE("Recorder names the file it cannot create") {
  try {
    ActuatorRecorder recorder("/nonexistent-dir/x.csv", "");
    FAIL("expected an error");
  } catch (const vt::Error& e) {
    CHECK(std::string(e.what()).find("/nonexistent-dir/x.csv") != std::string::npos);
  }
}
