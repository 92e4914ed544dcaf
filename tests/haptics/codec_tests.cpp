#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "codec_rate.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/codec/codec.hpp"
#include "vt/haptics/codec/psychohaptic.hpp"
#include "vt/haptics/codec/stream_codec.hpp"
#include "vt/haptics/codec/test_signals.hpp"

using namespace vt::haptics;

namespace {
constexpr int kSignalSamples = kRate * 2;

CodecConfig config(CodecId id, int quality = 50, int channels = 1, int block_ms = 4) {
  CodecConfig c;
  c.id = id;
  c.quality = quality;
  c.channels = channels;
  c.block_ms = block_ms;
  return c;
}
}  // namespace

TEST_CASE("Raw float32 is exact and 16-bit PCM is within one LSB") {
  const auto signal = textureSweepSignal(0.05f, 0.25f, 0.9f, kSignalSamples, kRate);
  const auto raw = evaluateCodec(config(CodecId::RawFloat32, 50, 3), signal);
  CHECK(raw.snr_db == 200.0);
  CHECK(raw.ratio == Approx(0.5));
  const auto pcm = evaluateCodec(config(CodecId::Pcm16, 50, 3), signal);
  CHECK(pcm.ratio == Approx(1.0));
  CHECK(pcm.snr_db > 85.0);
}

TEST_CASE("The perceptual codec reaches 10 to 1 at 20 dB on texture sweeps") {
  for (const auto& [start, end] : {std::pair{0.02f, 0.08f}, std::pair{0.05f, 0.25f}}) {
    const auto signal = textureSweepSignal(start, end, 0.8f, kSignalSamples, kRate);
    const auto report = evaluateCodec(config(CodecId::Perceptual), signal);
    INFO("speed " << start << ".." << end << " m/s: ratio " << report.ratio << " snr " << report.snr_db);
    CHECK(report.ratio >= 10.0);
    CHECK(report.snr_db >= 20.0);
  }
}

TEST_CASE("The perceptual codec keeps sines and band noise recognisable with SNR bounds") {
  for (float f : {80.0f, 250.0f, 400.0f}) {
    const auto report = evaluateCodec(config(CodecId::Perceptual), sineSignal(f, 0.5f, kSignalSamples, kRate));
    INFO(f << " Hz: ratio " << report.ratio << " snr " << report.snr_db);
    CHECK(report.snr_db >= 18.0);
    CHECK(report.ratio >= 5.0);
  }
  const auto noise = evaluateCodec(config(CodecId::Perceptual), bandNoiseSignal(50, 800, 0.2f, kSignalSamples, kRate, 7));
  INFO("band noise: ratio " << noise.ratio << " snr " << noise.snr_db);
  CHECK(noise.snr_db >= 15.0);
  CHECK(noise.ratio >= 4.0);
}

TEST_CASE("Higher quality spends more bits for less noise") {
  const auto signal = textureSweepSignal(0.05f, 0.25f, 0.8f, kSignalSamples, kRate);
  const auto low = evaluateCodec(config(CodecId::Perceptual, 20), signal);
  const auto high = evaluateCodec(config(CodecId::Perceptual, 80), signal);
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

TEST_CASE("Codec configs are checked field by field") {
  CHECK(checkCodecConfig(CodecConfig{}).empty());
  for (int ms : kCodecBlockLengths_ms) CHECK(framesPerBlock(config(CodecId::Perceptual, 50, 5, ms)) == ms / 4);
  auto bad = config(CodecId::Perceptual);
  bad.block_ms = 12;
  CHECK(checkCodecConfig(bad).find("block length") != std::string_view::npos);
  CHECK(framesPerBlock(bad) == 0);
  CHECK_THROWS_AS(makeBlockEncoder(bad), vt::Error);
  bad = config(CodecId::Perceptual);
  bad.frameLength = 24;  // 32 samples are not a whole number of 24-sample frames
  CHECK(checkCodecConfig(bad).find("whole number") != std::string_view::npos);
  bad = config(CodecId::Perceptual, 50, 11);
  CHECK(checkCodecConfig(bad).find("channels") != std::string_view::npos);
  bad = config(CodecId(7));
  CHECK(checkCodecConfig(bad).find("codec") != std::string_view::npos);
  bad = config(CodecId::Perceptual, 50, 1, 128);
  bad.sampleRate_hz = 48000;  // 6144 samples
  CHECK(checkCodecConfig(bad).find("4096") != std::string_view::npos);
  CHECK(maxPacketBytes(config(CodecId::Pcm16, 50, 5, 16)) == 5 * 128 * 2);
}

TEST_CASE("A 4 ms perceptual packet is the per-frame codec's block") {
  const auto signal = textureSweepSignal(0.05f, 0.25f, 0.8f, 32 * 40, kRate);
  const auto codec = makeCodec(CodecId::Perceptual, 50);
  const auto encoder = makeBlockEncoder(config(CodecId::Perceptual, 50, 3));
  for (std::size_t start = 0; start < signal.size(); start += 32) {
    WaveBlock block{};
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < 32; ++i)
        block[std::size_t(c)][std::size_t(i)] = (1.0f - 0.2f * float(c)) * signal[start + std::size_t(i)];
    std::array<std::uint8_t, kMaxEncodedBlock> bytes{};
    const std::size_t size = codec->encode(block, {3, 32, kRate}, bytes);
    REQUIRE(encoder->push(block));
    REQUIRE(encoder->packet().size() == size);
    CHECK(std::equal(bytes.begin(), bytes.begin() + std::ptrdiff_t(size), encoder->packet().begin()));
  }
}

TEST_CASE("Every codec and block length round-trips frame by frame") {
  const auto signal = textureSweepSignal(0.05f, 0.25f, 0.8f, kRate, kRate);
  for (auto id : {CodecId::RawFloat32, CodecId::Pcm16, CodecId::Perceptual}) {
    for (int ms : kCodecBlockLengths_ms) {
      const auto report = evaluateCodec(config(id, 60, 2, ms), signal);
      INFO(codecName(id) << " " << ms << " ms: snr " << report.snr_db << " ratio " << report.ratio);
      CHECK(report.snr_db >= (id == CodecId::Perceptual ? 20.0 : 85.0));
      CHECK(report.decoded.size() == signal.size() / std::size_t(ms * 8) * std::size_t(ms * 8));
    }
  }
  // Lengths that are not powers of two take the DCT's table path: 6 kHz, 24-sample frames.
  const auto slow = textureSweepSignal(0.05f, 0.25f, 0.8f, 6000, 6000);
  for (int ms : {4, 16, 64}) {
    auto c = config(CodecId::Perceptual, 60, 2, ms);
    c.sampleRate_hz = 6000;
    c.frameLength = 24;
    const auto report = evaluateCodec(c, slow);
    INFO(ms << " ms at 6 kHz: snr " << report.snr_db);
    CHECK(report.snr_db >= 20.0);
  }
}

TEST_CASE("The encoder emits one packet per block, flushes partial blocks and resets") {
  const auto encoder = makeBlockEncoder(config(CodecId::Perceptual, 50, 1, 16));
  const auto decoder = makeBlockDecoder(config(CodecId::Perceptual, 50, 1, 16));
  CHECK(decoder->frameCount() == 4);
  WaveBlock frame{};
  for (int i = 0; i < 32; ++i) frame[0][std::size_t(i)] = 0.5f * std::sin(0.3f * float(i));
  CHECK_FALSE(encoder->flush());
  CHECK_FALSE(encoder->push(frame));
  CHECK(encoder->pending() == 1);
  REQUIRE(encoder->flush());
  CHECK(encoder->pending() == 0);
  REQUIRE(decoder->decode(encoder->packet()));
  CHECK(decoder->frame(0)[0][3] == Approx(frame[0][3]).margin(0.05));
  for (int f = 1; f < 4; ++f)
    for (float v : decoder->frame(f)[0]) CHECK(std::fabs(v) < 0.05f);  // padded with silence
  encoder->push(frame);
  encoder->reset();
  CHECK(encoder->pending() == 0);
  CHECK(encoder->packet().empty());
  const auto raw = makeBlockDecoder(config(CodecId::Pcm16, 50, 1, 8));
  std::array<std::uint8_t, 100> odd{};
  CHECK_FALSE(raw->decode(odd));
}

TEST_CASE("Quality is monotone at every block length") {
  const auto signal = textureSweepSignal(0.05f, 0.25f, 0.8f, kSignalSamples, kRate);
  for (int ms : kCodecBlockLengths_ms) {
    double previousSnr = 0.0, previousKbps = 0.0;
    for (int quality = 0; quality <= 100; quality += 10) {
      const auto report = evaluateCodec(config(CodecId::Perceptual, quality, 1, ms), signal);
      INFO(ms << " ms quality " << quality << ": snr " << report.snr_db << " kbit/s " << report.bitrate_kbps);
      CHECK(report.snr_db > previousSnr + 2.0);
      CHECK(report.bitrate_kbps > previousKbps);
      previousSnr = report.snr_db;
      previousKbps = report.bitrate_kbps;
    }
  }
}

TEST_CASE("Longer blocks need fewer bits for the same texture quality") {
  const auto signal = textureSweepSignal(0.05f, 0.25f, 0.8f, kSignalSamples, kRate);
  const auto at4 = evaluateCodec(config(CodecId::Perceptual), signal);
  const auto at16 = evaluateCodec(config(CodecId::Perceptual, 50, 1, 16), signal);
  const auto at128 = evaluateCodec(config(CodecId::Perceptual, 50, 1, 128), signal);
  INFO(at4.bitrate_kbps << " " << at16.bitrate_kbps << " " << at128.bitrate_kbps);
  CHECK(at16.snr_db >= at4.snr_db);
  CHECK(at128.snr_db >= at4.snr_db);
  // Margins against the 4 ms block as coded since the trained context priors (which made the
  // 4 ms block ~25 % cheaper, longer blocks little): 0.76 and 0.56 measured.
  CHECK(at16.bitrate_kbps < 0.8 * at4.bitrate_kbps);
  CHECK(at128.bitrate_kbps < 0.65 * at4.bitrate_kbps);
}

TEST_CASE("Correlated actuators are coded jointly") {
  const auto signal = textureSweepSignal(0.05f, 0.25f, 0.8f, kSignalSamples, kRate);
  std::vector<std::vector<float>> five(5, signal);
  for (std::size_t c = 1; c < five.size(); ++c)
    for (float& v : five[c]) v *= 1.0f - 0.1f * float(c);  // the same texture, weaker further out
  for (int ms : {4, 32}) {
    const auto one = evaluateCodec(config(CodecId::Perceptual, 50, 1, ms), signal);
    const auto joint = evaluateCodec(config(CodecId::Perceptual, 50, 5, ms), five);
    INFO(ms << " ms: one channel " << one.bitrate_kbps << " kbit/s, five: " << joint.bitrate_kbps << " per channel");
    CHECK(joint.bitrate_kbps < 0.7 * one.bitrate_kbps);  // 0.66 at 4 ms since the trained priors
    CHECK(joint.snr_db >= one.snr_db - 1.0);
  }
}

TEST_CASE("Block decoders keep garbage bounded at every block length") {
  std::mt19937 rng(5);
  for (int ms : kCodecBlockLengths_ms) {
    const auto decoder = makeBlockDecoder(config(CodecId::Perceptual, 50, kMaxActuators, ms));
    for (int trial = 0; trial < 40; ++trial) {
      std::vector<std::uint8_t> bytes(rng() % 600);
      for (auto& b : bytes) b = std::uint8_t(rng());
      REQUIRE(decoder->decode(bytes));
      for (int f = 0; f < decoder->frameCount(); ++f)
        for (const auto& channel : decoder->frame(f))
          for (float v : channel) REQUIRE((std::isfinite(v) && v >= -1.0f && v <= 1.0f));
    }
  }
}
