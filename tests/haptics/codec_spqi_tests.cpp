// SPQI (haptics/codec/include/vt/haptics/codec/spqi.hpp): the published examples, the perfect
// score, and monotone scores over the codec's quality setting.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "codec_rate.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/codec/spqi.hpp"
#include "vt/haptics/codec/stream_codec.hpp"
#include "vt/haptics/codec/test_signals.hpp"

using namespace vt::haptics;

TEST_CASE("The SPQI threshold curve reproduces the reference implementation's published values") {
  // vibromaf tests/signal/test_perception.py: 10 bins at 2800 Hz end flat at 22.2531702551794 dB;
  // at 0 Hz every bin sits at the curve's 0 Hz value, -15 dB.
  const auto t = spqiThreshold_db(10, 2800.0);
  REQUIRE(t.size() == 10);
  for (int k = 6; k < 10; ++k) CHECK(t[std::size_t(k)] == Approx(22.253170255179413).epsilon(1e-12));
  for (double v : spqiThreshold_db(10, 0.0)) CHECK(v == Approx(-15.0).epsilon(1e-12));
  // The curve's minimum is the Pacinian peak, -77 dB at 250 Hz.
  const auto fine = spqiThreshold_db(kSpqiBlock, 8000.0);
  const auto lowest = std::min_element(fine.begin(), fine.end());
  CHECK(*lowest == Approx(-77.0).margin(0.01));
  CHECK(double(lowest - fine.begin()) * 8000.0 / (2 * kSpqiBlock - 1) == Approx(250.0).margin(8.0));
}

TEST_CASE("SPQI of identical signals is exactly 1, and bad lengths are refused") {
  const auto s = textureSweepSignal(0.05f, 0.25f, 0.8f, kRate, kRate);
  CHECK(spqi(s, s) == 1.0);
  std::vector<float> longer = s;
  longer.insert(longer.end(), 300, 0.5f);  // past the reference's end: cut off
  CHECK(spqi(s, longer) == 1.0);
  CHECK_THROWS_AS(spqi(std::vector<float>(s.begin(), s.begin() + 511), s), vt::Error);
  CHECK_THROWS_AS(spqi(s, std::vector<float>(s.begin(), s.end() - 1)), vt::Error);
}

TEST_CASE("SPQI reproduces the authors' white-noise example (about 0.43)") {
  // vibromaf docs/get-started.md (written for its 2800 Hz threshold, v0.0.5): reference = 1000 +
  // unit white noise, 1000 samples (one block); distorted = reference + unit white noise; "Should
  // be around 0.43". The noise is random, so the mean over 40 draws (its spread: sd 0.08).
  double sum = 0.0;
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    std::vector<float> reference(1000), distorted(1000);
    for (std::size_t i = 0; i < reference.size(); ++i) {
      reference[i] = 1000.0f + noise(rng);
      distorted[i] = reference[i] + noise(rng);
    }
    sum += spqi(reference, distorted, 2800.0);
  }
  CHECK(sum / 40.0 == Approx(0.43).margin(0.04));
}

TEST_CASE("SPQI falls as noise is added") {
  const auto s = textureSweepSignal(0.05f, 0.25f, 0.8f, kRate * 2, kRate);
  std::mt19937 rng(3);
  std::normal_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> noise(s.size());
  for (float& v : noise) v = unit(rng);
  double previous = 1.0;
  for (float level : {0.001f, 0.01f, 0.03f, 0.1f, 0.3f}) {
    std::vector<float> noisy(s);
    for (std::size_t i = 0; i < s.size(); ++i) noisy[i] += level * noise[i];
    const double score = spqi(s, noisy);
    INFO("noise rms " << level << ": SPQI " << score);
    CHECK(score < previous);
    previous = score;
  }
}

TEST_CASE("SPQI of coded signals rises with the codec's quality") {
  // Monotone for textures and noise at every block length tried (within 1e-4 where the score
  // saturates near 1). A pure 250 Hz tone, where the metric is most sensitive, is not: at 4 ms
  // quality 20 -> 30 scores 0.780 -> 0.774 and 40 -> 50 0.996 -> 0.990 (the codec's SNR itself
  // falls 23.50 -> 23.48 dB there: its 6 dB gain steps); for it only the trend is checked.
  const auto texture = textureSweepSignal(0.05f, 0.25f, 0.8f, kRate * 2, kRate);
  const auto noise = bandNoiseSignal(50.0f, 800.0f, 0.2f, kRate * 2, kRate, 7);
  const auto tone = sineSignal(250.0f, 0.5f, kRate * 2, kRate);
  for (int block_ms : {4, 32, 128}) {
    CodecConfig config;
    config.block_ms = block_ms;
    for (const auto* signal : {&texture, &noise}) {
      double previous = 0.0;
      for (int quality = 0; quality <= 100; quality += 10) {
        config.quality = quality;
        const auto report = evaluateCodec(config, *signal);
        INFO((signal == &texture ? "texture" : "band noise") << ", " << block_ms << " ms, quality " << quality
                                                              << ": SPQI " << report.spqi << ", SNR " << report.snr_db);
        CHECK(report.spqi >= previous - 1e-4);
        CHECK(report.spqi <= 1.0);
        previous = report.spqi;
      }
    }
    std::vector<double> toneScores;
    for (int quality : {10, 50, 90}) {
      config.quality = quality;
      toneScores.push_back(evaluateCodec(config, tone).spqi);
    }
    INFO("250 Hz tone, " << block_ms << " ms: SPQI " << toneScores[0] << " / " << toneScores[1] << " / " << toneScores[2]);
    CHECK(toneScores[0] < toneScores[2]);
    CHECK(toneScores[0] <= toneScores[1] + 1e-4);
    CHECK(toneScores[1] <= toneScores[2] + 1e-4);
  }
}

TEST_CASE("SPQI matches the authors' reference implementation on three distortions") {
  // Scores from vibromaf (commit 91c8684, the paper authors' implementation) of these signals,
  // computed in float64 from the same float32 samples: 0.5 sin(180 Hz) + 0.2 sin(700 Hz + 1) +
  // 0.05 LCG noise, distorted by a 250 Hz tone, by more noise, and by a 0.9 gain.
  constexpr std::size_t n = 4000;
  const auto lcg = [](std::uint64_t seed) {
    std::vector<double> out(n);
    for (double& v : out) {
      seed = (1103515245u * seed + 12345u) % (1u << 31);
      v = double(seed) / double(1u << 31) - 0.5;
    }
    return out;
  };
  const double pi = 3.141592653589793;
  const auto noise1 = lcg(1), noise7 = lcg(7);
  std::vector<float> reference(n), tone(n), noisy(n), scaled(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = double(i);
    const double r = 0.5 * std::sin(2 * pi * 180 * t / 8000) + 0.2 * std::sin(2 * pi * 700 * t / 8000 + 1.0) + 0.05 * noise1[i];
    reference[i] = float(r);
    tone[i] = float(double(reference[i]) + 0.1 * std::sin(2 * pi * 250 * t / 8000));
    noisy[i] = float(double(reference[i]) + 0.5 * noise7[i]);
    scaled[i] = float(0.9 * double(reference[i]));
  }
  CHECK(spqi(reference, tone) == Approx(0.894862827969962).margin(1e-5));
  CHECK(spqi(reference, noisy) == Approx(0.9015825835539545).margin(1e-5));
  CHECK(spqi(reference, scaled) == Approx(0.5811457049872898).margin(1e-5));
}
