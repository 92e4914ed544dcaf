#pragma once
// Test signals for the tactile codecs (tests and vt_bench) and a harness that runs a codec
// block by block over a signal and reports compression ratio, SNR and coding time.
#include <cstdint>
#include <string>
#include <vector>

#include "vt/haptics/codec/stream_codec.hpp"

namespace vt::haptics {

/// amplitude * sin(2 pi f t).
std::vector<float> sineSignal(float frequency_hz, float amplitude, int samples, int sampleRate_hz);
/// Noise with a flat spectrum between lo and hi (a sum of random-phase sines), scaled to rms.
std::vector<float> bandNoiseSignal(float lo_hz, float hi_hz, float rms, int samples, int sampleRate_hz,
                                   std::uint32_t seed);
/// Height of a stripe + value-noise texture map (0..1) at a point in metres.
float textureHeight(float x_m, float y_m) noexcept;
/// A texture sweep: textureHeight sampled along a path sliding in x at a speed ramping from
/// speedStart to speedEnd (m/s), mean removed, scaled to peak `amplitude`.
std::vector<float> textureSweepSignal(float speedStart_m_s, float speedEnd_m_s, float amplitude, int samples,
                                      int sampleRate_hz);

/// 10 log10(sum ref^2 / sum (ref - test)^2); 200 dB for an exact match.
double snr_db(const std::vector<float>& reference, const std::vector<float>& test);

/// What one codec did to one signal.
struct CodecReport {
  double ratio = 0.0;          // 16-bit PCM bytes / encoded bytes
  double snr_db = 0.0;
  double spqi = 0.0;           // SPQI (spqi.hpp), mean over channels; NaN below one SPQI block
  double encode_us_per_block = 0.0;
  double decode_us_per_block = 0.0;
  double bitrate_kbps = 0.0;   // per channel
  std::vector<float> decoded;  // channel 0
};

/// Codes `channels` (config.channels signals of equal length) through a BlockEncoder and
/// BlockDecoder of `config`, whole blocks only; SNR over every channel, SPQI per channel
/// (averaged), times per packet.
/// Throws vt::Error when the decoder rejects the encoder's output.
CodecReport evaluateCodec(const CodecConfig& config, const std::vector<std::vector<float>>& channels);
/// The same with `signal` copied to every channel of the config.
CodecReport evaluateCodec(const CodecConfig& config, const std::vector<float>& signal);

}  // namespace vt::haptics
