#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "vt/core/error.hpp"
#include "vt/haptics/codec/codec.hpp"
#include "vt/haptics/codec/psychohaptic.hpp"
#include "vt/haptics/codec/test_signals.hpp"

using namespace vt::haptics;

namespace {
constexpr int kRate = 8000;
constexpr int kSamples = kRate * 2;
}  // namespace

TEST_CASE("Raw float32 is exact and 16-bit PCM is within one LSB") {
  const auto signal = textureSweepSignal(0.05f, 0.25f, 0.9f, kSamples, kRate);
  const auto raw = evaluateCodec(*makeCodec(CodecId::RawFloat32), signal, 32, kRate, 3);
  CHECK(raw.snr_db == 200.0);
  CHECK(raw.ratio == Approx(0.5));
  const auto pcm = evaluateCodec(*makeCodec(CodecId::Pcm16), signal, 32, kRate, 3);
  CHECK(pcm.ratio == Approx(1.0));
  CHECK(pcm.snr_db > 85.0);
}

TEST_CASE("The perceptual codec reaches 10 to 1 at 20 dB on texture sweeps") {
  const auto codec = makeCodec(CodecId::Perceptual, 50);
  for (const auto& [start, end] : {std::pair{0.02f, 0.08f}, std::pair{0.05f, 0.25f}}) {
    const auto signal = textureSweepSignal(start, end, 0.8f, kSamples, kRate);
    const auto report = evaluateCodec(*codec, signal, 32, kRate);
    INFO("speed " << start << ".." << end << " m/s: ratio " << report.ratio << " snr " << report.snr_db);
    CHECK(report.ratio >= 10.0);
    CHECK(report.snr_db >= 20.0);
  }
}

TEST_CASE("The perceptual codec keeps sines and band noise recognisable with SNR bounds") {
  const auto codec = makeCodec(CodecId::Perceptual, 50);
  for (float f : {80.0f, 250.0f, 400.0f}) {
    const auto report = evaluateCodec(*codec, sineSignal(f, 0.5f, kSamples, kRate), 32, kRate);
    INFO(f << " Hz: ratio " << report.ratio << " snr " << report.snr_db);
    CHECK(report.snr_db >= 18.0);
    CHECK(report.ratio >= 5.0);
  }
  const auto noise = evaluateCodec(*codec, bandNoiseSignal(50, 800, 0.2f, kSamples, kRate, 7), 32, kRate);
  INFO("band noise: ratio " << noise.ratio << " snr " << noise.snr_db);
  CHECK(noise.snr_db >= 15.0);
  CHECK(noise.ratio >= 4.0);
}

TEST_CASE("Higher quality spends more bits for less noise") {
  const auto signal = textureSweepSignal(0.05f, 0.25f, 0.8f, kSamples, kRate);
  const auto low = evaluateCodec(*makeCodec(CodecId::Perceptual, 20), signal, 32, kRate);
  const auto high = evaluateCodec(*makeCodec(CodecId::Perceptual, 80), signal, 32, kRate);
  CHECK(high.snr_db > low.snr_db + 8.0);
  CHECK(high.ratio < low.ratio);
  CHECK_THROWS_AS(makeCodec(CodecId::Perceptual, 101), vt::Error);
  CHECK_THROWS_AS(makeCodec(CodecId(9)), vt::Error);
}

TEST_CASE("Every block length and channel count round-trips and silent channels stay silent") {
  const auto codec = makeCodec(CodecId::Perceptual, 60);
  const auto signal = textureSweepSignal(0.05f, 0.2f, 0.7f, 64, kRate);
  for (int length = 1; length <= kMaxBlockSamples; ++length) {
    for (int channels : {1, 4, kMaxActuators}) {
      WaveBlock block{}, decoded{};
      for (int c = 0; c < channels; c += 2)  // odd channels silent
        for (int i = 0; i < length; ++i) block[std::size_t(c)][std::size_t(i)] = signal[std::size_t(i + c)];
      std::array<std::uint8_t, kMaxEncodedBlock> bytes{};
      const BlockFormat format{channels, length, kRate};
      const std::size_t size = codec->encode(block, format, bytes);
      REQUIRE(codec->decode(std::span(bytes.data(), size), format, decoded));
      double energy = 0, noise = 0;
      for (int c = 0; c < kMaxActuators; ++c) {
        for (int i = 0; i < kMaxBlockSamples; ++i) {
          const float ref = block[std::size_t(c)][std::size_t(i)], out = decoded[std::size_t(c)][std::size_t(i)];
          if (c % 2 == 1 || c >= channels || i >= length) REQUIRE(out == 0.0f);
          energy += ref * ref;
          noise += (ref - out) * (ref - out);
        }
      }
      INFO("length " << length << " channels " << channels);
      if (length >= 8) CHECK(10.0 * std::log10(energy / std::max(noise, 1e-20)) >= 15.0);
    }
  }
}

TEST_CASE("Codec decoders reject wrong sizes and keep garbage bounded") {
  WaveBlock block{};
  std::array<std::uint8_t, 16> small{};
  CHECK_FALSE(makeCodec(CodecId::RawFloat32)->decode(small, {1, 8, kRate}, block));
  CHECK_FALSE(makeCodec(CodecId::Pcm16)->decode(small, {2, 8, kRate}, block));
  CHECK_FALSE(makeCodec(CodecId::Perceptual)->decode(small, {0, 8, kRate}, block));
  std::mt19937 rng(3);
  const auto codec = makeCodec(CodecId::Perceptual);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<std::uint8_t> bytes(rng() % 200);
    for (auto& b : bytes) b = std::uint8_t(rng());
    REQUIRE(codec->decode(bytes, {kMaxActuators, kMaxBlockSamples, kRate}, block));
    for (const auto& channel : block)
      for (float v : channel) REQUIRE((std::isfinite(v) && v >= -1.0f && v <= 1.0f));
  }
}

TEST_CASE("The psychohaptic threshold is lowest near 250 Hz") {
  CHECK(vibrotactileThreshold_db(250.0f) == Approx(0.0f).margin(1e-4));
  CHECK(vibrotactileThreshold_db(125.0f) == Approx(12.0f));
  CHECK(vibrotactileThreshold_db(1000.0f) == Approx(24.0f));
  CHECK(vibrotactileThreshold_db(10.0f) == vibrotactileThreshold_db(40.0f));
  for (float f = 20.0f; f < 4000.0f; f *= 1.1f) CHECK(vibrotactileThreshold_db(f) >= 0.0f);
}

TEST_CASE("Codec names parse back") {
  for (auto id : {CodecId::RawFloat32, CodecId::Pcm16, CodecId::Perceptual}) {
    CodecId parsed{};
    REQUIRE(parseCodecName(codecName(id), parsed));
    CHECK(parsed == id);
    CHECK(isKnownCodec(std::uint8_t(id)));
  }
  CHECK_FALSE(isKnownCodec(0));
}
