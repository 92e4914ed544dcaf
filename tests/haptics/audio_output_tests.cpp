#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <random>
#include <thread>
#include <vector>

#include "test_support.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/realtime.hpp"
#include "vt/haptics/devices/audio_output.hpp"
#include "vt/haptics/devices/recorder.hpp"

using namespace vt;
using namespace vt::haptics;

namespace {

constexpr std::uint32_t kInputRate_hz = 8000;
constexpr std::uint32_t kDeviceRate_hz = 48000;
constexpr int kBlock = 8;  // 1 kHz ticks

std::vector<std::int16_t> readInt16(const std::filesystem::path& path, std::size_t skipBytes) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::int16_t> samples((bytes.size() - std::min(bytes.size(), skipBytes)) / 2);
  for (std::size_t i = 0; i < samples.size(); ++i)
    samples[i] = std::int16_t(std::uint16_t(std::uint8_t(bytes[skipBytes + 2 * i])) | std::uint16_t(std::uint8_t(bytes[skipBytes + 2 * i + 1])) << 8);
  return samples;
}

/// Channel `c` of interleaved samples.
std::vector<double> channel(const std::vector<std::int16_t>& interleaved, int channels, int c) {
  std::vector<double> out(interleaved.size() / std::size_t(channels));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = interleaved[i * std::size_t(channels) + std::size_t(c)];
  return out;
}

struct Alignment {
  std::size_t offset = 0;    // device frames before the reference's first sample
  double correlation = 0.0;  // normalised cross-correlation at that offset
};

/// The offset into `captured` (device rate) where `reference` (input rate, every `ratio`-th
/// captured sample) matches best.
Alignment align(const std::vector<double>& captured, const std::vector<double>& reference, std::size_t ratio) {
  Alignment best;
  double refEnergy = 0.0;
  for (double r : reference) refEnergy += r * r;
  for (std::size_t offset = 0; offset + (reference.size() - 1) * ratio < captured.size(); ++offset) {
    double xy = 0.0, xx = 0.0;
    for (std::size_t i = 0; i < reference.size(); ++i) {
      const double x = captured[offset + i * ratio];
      xy += x * reference[i];
      xx += x * x;
    }
    const double c = xx > 0.0 ? xy / std::sqrt(xx * refEnergy) : 0.0;
    if (c > best.correlation) best = {offset, c};
  }
  return best;
}

}  // namespace

TEST_CASE("parseChannelMap maps device channels to actuators by name") {
  CHECK(parseChannelMap("thumb,index") == std::vector<int>{0, 1});
  CHECK(parseChannelMap("index,-,palm-little-down") == std::vector<int>{1, -1, 9});
  CHECK(parseChannelMap("little,pinky,palm-pinky-down") == std::vector<int>{4, 4, 9});  // older maps still work
  CHECK_THROWS_WITH(parseChannelMap("thumb,indx"), Catch::Contains("entry 2 'indx' is not an actuator"));
  CHECK_THROWS_WITH(parseChannelMap(""), Catch::Contains("entry 1 '' is not an actuator"));
}

TEST_CASE("AudioOutput names the device it cannot open") {
  AudioOutputConfig config;
  config.device = "no-such-vtouching-device";
  CHECK_THROWS_WITH(AudioOutput(config), Catch::Contains("audio device 'no-such-vtouching-device': cannot open"));
}

namespace {

// One channel with a jitter buffer that rides out a loaded test machine, on a device that fails.
AudioOutputConfig failingDeviceConfig(std::string device) {
  AudioOutputConfig config;
  config.device = std::move(device);
  config.channels = parseChannelMap("index");
  config.rate_hz = kDeviceRate_hz;
  config.latency_us = 20000;
  return config;
}

/// Feeds the output one frame and waits for its first write error.
void startUntilError(AudioOutput& output) {
  ActuatorFrame frame;
  frame.actuatorCount = 5;
  frame.blockLength = kBlock;
  frame.sampleRate_hz = kInputRate_hz;
  REQUIRE(output.queue().push(frame));
  REQUIRE(vt::test::eventually([&] { return !output.status().lastError.empty(); }));
}

}  // namespace

// ALSA's file plugin writing to /dev/full: the device takes the stream, then every few periods
// a write fails (EIO), as a USB interface that is unplugged mid-stream does.
TEST_CASE("AudioOutput reports a failing device's write error in its status, keeps going and stops") {
  if (!std::filesystem::exists("/dev/full")) VT_SKIP("no /dev/full in this container");
  AudioOutput output(failingDeviceConfig("file:FILE=/dev/full,FORMAT=raw"));
  startUntilError(output);
  const std::uint64_t written = output.status().framesWritten;
  // The writer waits after a failed write and tries again: the stream goes on.
  REQUIRE(vt::test::eventually([&] { return output.status().framesWritten > written; }));
  output.stop();
  const AudioOutputStatus s = output.status();
  CHECK(s.reopens >= 1);
  CHECK(s.lastError == "write failed: Input/output error");
  CHECK_THAT(output.statusLine(), Catch::StartsWith("audio file:FILE=/dev/full,FORMAT=raw 1 ch ") &&
                                      Catch::EndsWith(", write failed: Input/output error"));
}

// ALSA's file plugin writing into a folder that does not exist yet fails its writes and its
// handle stays failed once the folder exists (it does not open its file again): the case of a
// USB interface unplugged and plugged back. The output opens the device anew and plays on.
TEST_CASE("AudioOutput opens a device anew when its handle failed, and plays into it once it is back") {
  const auto dir = test::outputDir("audio_output_reopen");
  std::filesystem::remove_all(dir / "later");
  const auto capture = dir / "later" / "capture.raw";
  AudioOutput output(failingDeviceConfig(str("file:FILE=", capture.string(), ",FORMAT=raw")));
  startUntilError(output);
  CHECK_FALSE(std::filesystem::exists(capture));
  std::filesystem::create_directories(dir / "later");  // the device is back
  REQUIRE(vt::test::eventually([&] {
    std::error_code ec;
    return std::filesystem::file_size(capture, ec) > 0 && !ec;
  }));
  output.stop();
  const AudioOutputStatus s = output.status();
  CHECK(s.reopens >= 1);
  CHECK_THAT(output.statusLine(), Catch::Contains(", reopened "));
}

// The headless audio interface: ALSA's file plugin (on its null device) captures exactly what
// the output writes. The same frames go through ActuatorRecorder, the --record-wav writer, and
// the capture must be that recording resampled, on the mapped channels, then silence.
TEST_CASE("AudioOutput plays each actuator's waveform on its mapped channel, as --record-wav records it") {
  const auto dir = test::outputDir("audio_output_capture");
  const auto capture = dir / "capture.raw";
  AudioOutputConfig config;
  config.device = str("file:FILE=", capture.string(), ",FORMAT=raw");
  config.channels = parseChannelMap("index,-,thumb");
  config.rate_hz = kDeviceRate_hz;
  config.latency_us = 20000;  // a jitter buffer that rides out a loaded test machine
  config.failsafe.stallTimeout_ns = 200'000'000;
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.0f, 0.25f);
  {
    AudioOutput output(config);
    ActuatorRecorder recorder("", dir / "record.wav", 5);
    // Low-passed noise per actuator: no period, so the alignment below has one clear peak.
    std::vector<ActuatorFrame> frames(600);
    std::array<float, 5> state{};
    for (std::size_t tick = 0; tick < frames.size(); ++tick) {
      ActuatorFrame& frame = frames[tick];
      frame.sequence = tick;
      frame.actuatorCount = 5;
      frame.blockLength = kBlock;
      frame.sampleRate_hz = kInputRate_hz;
      for (int a = 0; a < 5; ++a) {
        for (int i = 0; i < kBlock; ++i) {
          state[std::size_t(a)] += 0.3f * (noise(rng) - state[std::size_t(a)]);
          frame.block[std::size_t(a)][std::size_t(i)] = std::clamp(state[std::size_t(a)], -1.0f, 1.0f);
        }
        frame.intensity[std::size_t(a)] = 0.5f;
      }
    }
    // Fed at 1 kHz from a thread standing in for the haptic loop (real time where allowed, as
    // the loop would be).
    int refused = 0;
    std::thread feeder([&] {
      requestRealtime("audio test feeder", 20);
      const std::int64_t start = SteadyClock::instance().now_ns();
      for (std::size_t tick = 0; tick < frames.size(); ++tick) {
        SteadyClock::instance().sleepUntil(start + std::int64_t(tick) * 1'000'000);
        if (!output.queue().push(frames[tick])) ++refused;
      }
    });
    feeder.join();
    CHECK(refused == 0);
    for (const ActuatorFrame& frame : frames) recorder.record(frame);
    recorder.finish();
    output.stop();
    const AudioOutputStatus s = output.status();
    CHECK(s.channels == 3);
    CHECK(s.rate_hz == kDeviceRate_hz);
    CHECK_FALSE(s.clocked);  // the null device: paced by the steady clock
    CHECK(s.lastError.empty());
    CHECK(s.underruns == 0);
    WARN("audio output: starved frames " << s.starvedFrames << ", skipped input samples " << s.skippedSamples);
  }
  const auto captured = readInt16(capture, 0);
  const auto recorded = readInt16(dir / "record.wav", 44);
  REQUIRE(recorded.size() == 600u * kBlock * 5);
  REQUIRE(captured.size() % 3 == 0);
  const std::size_t ratio = kDeviceRate_hz / kInputRate_hz;
  // Windows of 50 ms from 125 ms into the feed (the stream is playing by then), each aligned on
  // its own: a loaded machine may starve the stream for a moment, which shifts what follows.
  const auto index = channel(captured, 3, 0), thumb = channel(captured, 3, 2);
  const auto recordedIndex = channel(recorded, 5, 1), recordedThumb = channel(recorded, 5, 0);
  constexpr std::size_t kWindow = 400, kFirst = 1000, kWindows = 8;
  int matching = 0;
  double firstLatency_ms = 0.0;
  for (std::size_t w = 0; w < kWindows; ++w) {
    const std::size_t start = kFirst + w * kWindow;
    const auto part = [&](const std::vector<double>& v) {
      return std::vector<double>(v.begin() + std::ptrdiff_t(start), v.begin() + std::ptrdiff_t(start + kWindow));
    };
    const Alignment i = align(index, part(recordedIndex), ratio);
    const Alignment t = align(thumb, part(recordedThumb), ratio);
    // Latency: the window was fed start / 8 kHz after the start; the null device took its first
    // four buffers at once and counts as full from then on, so capture frame f plays
    // (f - 3 buffers) / rate after the start.
    const double latency_ms = (double(i.offset) - 3.0 * double(config.latency_us) * kDeviceRate_hz / 1e6) / kDeviceRate_hz * 1e3 -
                              double(start) * 1e3 / kInputRate_hz;
    if (w == 0) firstLatency_ms = latency_ms;
    // The same samples up to 16-bit rounding, both channels in step.
    if (i.correlation > 0.999 && t.correlation > 0.999 && i.offset == t.offset) ++matching;
    else WARN("window " << w << ": correlation index " << i.correlation << ", thumb " << t.correlation);
  }
  // An upper bound: the device clock starts a little before the feeder thread does.
  WARN("audio capture: " << matching << " of " << kWindows << " windows match (correlation > 0.999); latency at most "
       << firstLatency_ms << " ms (jitter buffer + device buffer: " << 2 * config.latency_us / 1000 << " ms)");
  CHECK(matching >= int(kWindows) - 2);  // at most two windows may straddle a starved moment
  for (std::size_t f = 0; f < captured.size() / 3; ++f) REQUIRE(captured[f * 3 + 1] == 0);  // "-": silent
  // Silence on exit: the last period the device got is all zeros.
  const std::size_t tail = 3 * 200;
  REQUIRE(captured.size() > tail);
  for (std::size_t i = captured.size() - tail; i < captured.size(); ++i) REQUIRE(captured[i] == 0);
}
