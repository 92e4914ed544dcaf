#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "vt/haptics/tactile_model.hpp"

using namespace vt;
using namespace vt::haptics;

namespace {

VibrationMap constantMap(float value) {
  const std::vector<float> values(4, value);
  return vibrationMapFromFloats(2, 2, values, "constant");
}

// Sinusoidal stripes along u: `periods` full periods across the map.
VibrationMap stripeMap(int width, int periods) {
  std::vector<float> values(std::size_t(width) * 4);
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < width; ++col) {
      const float u = (float(col) + 0.5f) / float(width);
      values[std::size_t(row * width + col)] = 0.5f + 0.5f * std::sin(2.0f * std::numbers::pi_v<float> * float(periods) * u);
    }
  }
  return vibrationMapFromFloats(width, 4, values, "stripes");
}

// Sweeps u at `speed` (uv units/s) for `seconds`, 1 kHz ticks of 8 samples; returns the signal.
std::vector<float> sweep(TactileModel& renderer, const VibrationMap& map, float speed, float seconds) {
  std::vector<float> signal;
  float block[8];
  ContactInput in{true, &map, true, {0.1f, 0.5f}, {0.1f, 0.5f}, 0.0f, 0.5f};
  for (int tick = 0; tick < int(seconds * 1000.0f); ++tick) {
    in.uvStart = in.uvEnd;
    in.uvEnd.x += speed / 1000.0f;
    renderer.render(in, block);
    signal.insert(signal.end(), block, block + 8);
  }
  return signal;
}

// Frequency of the largest DFT magnitude between 20 Hz and 2 kHz (1 Hz steps).
float dominantFrequency(const std::vector<float>& signal, float sampleRate) {
  float bestF = 0.0f, bestMag = -1.0f;
  for (float f = 20.0f; f < 2000.0f; f += 1.0f) {
    double re = 0.0, im = 0.0;
    const double w = 2.0 * std::numbers::pi * f / sampleRate;
    for (std::size_t i = 0; i < signal.size(); ++i) {
      re += signal[i] * std::cos(w * double(i));
      im += signal[i] * std::sin(w * double(i));
    }
    const float mag = float(re * re + im * im);
    if (mag > bestMag) bestMag = mag, bestF = f;
  }
  return bestF;
}

float rms(std::span<const float> s) {
  double e = 0.0;
  for (float x : s) e += double(x) * x;
  return s.empty() ? 0.0f : float(std::sqrt(e / double(s.size())));
}

}  // namespace

TEST_CASE("The paper intensity formula with depth modifier and gain") {
  CHECK(paperIntensity(0.8f, 0.0f, 0.5f) == Approx(0.4f));
  CHECK(paperIntensity(0.8f, 0.02f, 0.5f) == Approx(0.48f));   // 0.8 * 1.2 * 0.5
  CHECK(paperIntensity(0.8f, 0.05f, 0.5f) == Approx(0.5f));    // 0.8 * 1.5 = 1.2 -> 1, * 0.5
  CHECK(paperIntensity(0.5f, 0.2f, 1.0f) == Approx(0.75f));    // depth term saturates at 0.5
  CHECK(paperIntensity(0.5f, -0.01f, 1.0f) == Approx(0.5f));   // negative depth adds nothing
  CHECK(paperIntensity(0.3f, 0.01f, 0.25f) == Approx(0.3f * 1.1f * 0.25f));
  CHECK(paperIntensity(-0.2f, 0.0f, 1.0f) == 0.0f);
}

TEST_CASE("Paper model ramps on within 2 ms and releases to exact zero") {
  const VibrationMap map = constantMap(0.6f);
  TactileModel renderer({TactileModelKind::PaperIntensity, 8000.0f});
  float block[8];
  ContactInput in{true, &map, false, {0.5f, 0.5f}, {0.5f, 0.5f}, 0.01f, 0.5f};
  const float full = paperIntensity(0.6f, 0.01f, 0.5f);
  const ContactOutput first = renderer.render(in, block);
  CHECK(first.intensity > 0.0f);
  CHECK(first.intensity < full);  // ramping, no step
  CHECK(std::abs(block[0]) <= full / 16.0f + 1e-6f);
  const ContactOutput second = renderer.render(in, block);  // 2 ms = 16 samples at 8 kHz
  CHECK(second.intensity == Approx(full));
  CHECK(second.frequency_hz == Approx(250.0f));
  in.inContact = false;
  const ContactOutput releasing = renderer.render(in, block);
  CHECK(releasing.intensity > 0.0f);
  CHECK(releasing.intensity < full);
  const ContactOutput released = renderer.render(in, block);  // 16 samples after release
  CHECK(released.intensity == 0.0f);
  CHECK(block[7] == 0.0f);
  const ContactOutput after = renderer.render(in, block);
  CHECK(after.intensity == 0.0f);
  for (float s : block) CHECK(s == 0.0f);
}

TEST_CASE("Touching a surface without a vibration map gives silence") {
  TactileModel renderer;
  float block[8] = {1, 1, 1, 1, 1, 1, 1, 1};
  const ContactOutput out = renderer.render({true, nullptr, false, {}, {}, 0.01f, 0.5f}, block);
  CHECK(out.intensity == 0.0f);
  for (float s : block) CHECK(s == 0.0f);
}

TEST_CASE("Texture waveform frequency scales with sliding speed and rests silent") {
  const VibrationMap map = stripeMap(512, 64);  // spatial period 1/64 in u
  TactileModel slow({TactileModelKind::TextureWaveform, 8000.0f});
  TactileModel fast({TactileModelKind::TextureWaveform, 8000.0f});
  const std::vector<float> a = sweep(slow, map, 2.0f, 0.5f);  // 128 Hz
  const std::vector<float> b = sweep(fast, map, 4.0f, 0.5f);  // 256 Hz
  const float fa = dominantFrequency(a, 8000.0f), fb = dominantFrequency(b, 8000.0f);
  CHECK(fa == Approx(128.0f).epsilon(0.05));
  CHECK(fb == Approx(256.0f).epsilon(0.05));
  CHECK(fb / fa == Approx(2.0f).epsilon(0.05));
  CHECK(rms(std::span(b).subspan(b.size() / 2)) > 0.1f);
  // Standing still on the same stripes: the vibration dies away.
  const std::vector<float> rest = sweep(fast, map, 0.0f, 0.2f);
  CHECK(rms(std::span(rest).last(800)) < 1e-3f);
}

TEST_CASE("Taxel waveform playback reproduces the recorded waveform") {
  TaxelWaveforms waves;
  waves.samplesPerTaxel = 4;
  waves.peak_g = 1.0f;
  waves.samples = {0.5f, -0.5f, 0.25f, -0.25f, 0.0f, 0.0f, 0.0f, 0.0f};
  ImageF intensity(2, 1, 1);
  intensity.pixels = {1.0f, 0.0f};
  const VibrationMap map(intensity, "waves", waves);
  TactileModel renderer({TactileModelKind::TaxelWaveform, 8000.0f});
  float block[8];
  const ContactInput in{true, &map, false, {0.25f, 0.5f}, {0.25f, 0.5f}, 0.0f, 0.5f};
  renderer.render(in, block);  // ramp-up tick
  renderer.render(in, block);
  const ContactOutput out = renderer.render(in, block);
  for (int k = 0; k < 8; ++k) CHECK(block[k] == Approx(waves.samples[std::size_t(k % 4)]));
  CHECK(out.intensity == Approx(0.5f));  // paper level from the RMS-derived map
  const ContactInput other{true, &map, false, {0.75f, 0.5f}, {0.75f, 0.5f}, 0.0f, 0.5f};
  renderer.render(other, block);
  for (float s : block) CHECK(s == 0.0f);  // the silent taxel
}

TEST_CASE("The release ramp never reads the map it was touching") {
  // The loop may free an old scene snapshot while a finger is still fading out: every model
  // must release from cached state (ASan turns a stale read into a failure).
  for (TactileModelKind model : {TactileModelKind::PaperIntensity, TactileModelKind::TextureWaveform, TactileModelKind::TaxelWaveform}) {
    TaxelWaveforms waves;
    waves.samplesPerTaxel = 4;
    waves.peak_g = 1.0f;
    waves.samples = {0.5f, -0.5f, 0.25f, -0.25f};
    ImageF intensity(1, 1, 1);
    intensity.pixels = {1.0f};
    auto map = std::make_unique<VibrationMap>(intensity, "doomed", waves);
    TactileModel renderer({model, 8000.0f});
    float block[8];
    ContactInput in{true, map.get(), false, {0.5f, 0.5f}, {0.6f, 0.5f}, 0.0f, 0.5f};
    for (int i = 0; i < 3; ++i) renderer.render(in, block);
    map.reset();
    in = {};
    const ContactOutput fading = renderer.render(in, block);
    CHECK(fading.intensity >= 0.0f);
    for (float s : block) CHECK(std::isfinite(s));
    const ContactOutput done = renderer.render(in, block);
    CHECK(done.intensity == 0.0f);
    CHECK(block[7] == 0.0f);
  }
}

TEST_CASE("Two scan directions blend by the direction of motion") {
  const VibrationMap along = constantMap(0.8f), across = constantMap(0.2f);
  TactileModel renderer;
  std::array<float, 8> block{};
  const auto touch = [&](glm::vec2 from, glm::vec2 to) {
    ContactInput in;
    in.inContact = true;
    in.map = &along;
    in.mapAcross = &across;
    in.scanDirectionUv = {1.0f, 0.0f};
    in.uvStart = from, in.uvEnd = to;
    return renderer.render(in, block);
  };
  // Resting on first contact: no direction yet, the two maps weigh the same.
  ContactOutput out = touch({0.5f, 0.5f}, {0.5f, 0.5f});
  CHECK(out.acrossWeight == Approx(0.5f));
  CHECK(out.mapValue == Approx(0.5f));
  out = touch({0.5f, 0.5f}, {0.6f, 0.5f});  // along the scan direction
  CHECK(out.acrossWeight == Approx(0.0f).margin(1e-6));
  CHECK(out.mapValue == Approx(0.8f));
  out = touch({0.6f, 0.5f}, {0.6f, 0.4f});  // across it
  CHECK(out.acrossWeight == Approx(1.0f));
  CHECK(out.mapValue == Approx(0.2f));
  out = touch({0.6f, 0.4f}, {0.7f, 0.5f});  // diagonal (square map): cos^2 45 deg = 0.5
  CHECK(out.acrossWeight == Approx(0.5f));
  CHECK(out.mapValue == Approx(0.5f));
  out = touch({0.7f, 0.5f}, {0.7f, 0.5f});  // resting keeps the last direction
  CHECK(out.acrossWeight == Approx(0.5f));
  // A single map ignores direction entirely.
  ContactInput single;
  single.inContact = true;
  single.map = &along;
  single.uvStart = {0.1f, 0.1f}, single.uvEnd = {0.1f, 0.3f};
  out = renderer.render(single, block);
  CHECK(out.acrossWeight == 0.0f);
  CHECK(out.mapValue == Approx(0.8f));
}
