#pragma once
// Vibration maps: an intensity image (one channel, [0,1]) and optionally one short waveform
// per taxel. Immutable once loaded; the haptic thread samples them through const calls.
//
// UV convention (scene/mesh.hpp, the paper's Unity app): origin at the image's bottom-left,
// v up. Texel (col, row) covers u in [col/w, (col+1)/w] and v in [1-(row+1)/h, 1-row/h], i.e.
// row = (1 - v) * height, col = u * width; bilinear sampling is exact at texel centres.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "vt/scene/image.hpp"

namespace vt::haptics {

/// Per-taxel waveforms, all resampled to the same length, normalised to [-1, 1].
struct TaxelWaveforms {
  int samplesPerTaxel = 0;
  float peak_g = 0.0f;         // acceleration that maps to 1.0 (largest |sample| in the data)
  std::vector<float> samples;  // (row * width + col) * samplesPerTaxel + i

  bool empty() const noexcept { return samples.empty(); }
};

class VibrationMap {
 public:
  VibrationMap() = default;
  /// Takes a one-channel image in [0,1] (row 0 = top = v 1). `source` names it in errors.
  VibrationMap(ImageF intensity, std::string source, TaxelWaveforms waveforms = {});

  /// Bilinear intensity at (u, v); wrap repeats, clamp holds the border. Any thread.
  float sample(glm::vec2 uv, bool wrap) const noexcept;
  /// The taxel under (u, v) (nearest, by the row/col rule above). Any thread.
  glm::ivec2 taxel(glm::vec2 uv, bool wrap) const noexcept;
  /// The waveform of a taxel (empty span when the map has none). Any thread.
  std::span<const float> waveform(glm::ivec2 taxel) const noexcept;

  int width() const noexcept { return m_intensity.width; }
  int height() const noexcept { return m_intensity.height; }
  bool empty() const noexcept { return m_intensity.empty(); }
  const ImageF& intensity() const noexcept { return m_intensity; }
  const TaxelWaveforms& waveforms() const noexcept { return m_waveforms; }
  const std::string& source() const noexcept { return m_source; }

 private:
  ImageF m_intensity;
  TaxelWaveforms m_waveforms;
  std::string m_source;
};

/// PNG (8- or 16-bit, grey or RGB/RGBA: the red channel). Throws vt::Error naming the file.
VibrationMap loadVibrationMapPng(const std::filesystem::path& path);

/// From float data (row-major, top row first). Rejects wrong sizes and non-finite values;
/// clamps to [0,1]. `source` names the data in errors.
VibrationMap vibrationMapFromFloats(int width, int height, std::span<const float> values, const std::string& source);

/// Options for the per-taxel waveform files.
struct TaxelWaveformOptions {
  int samplesPerTaxel = 160;  // 20 ms (the reference app's physics frame) at 8 kHz
};

/// Loads `dir`/header.bin + `dir`/data.bin (little-endian int32 height, width, then
/// height*width start indices into data.bin; data.bin float32 accelerations in g). Subtracts
/// 1 g, resamples each taxel to samplesPerTaxel, normalises by the peak, and derives the
/// intensity image from each taxel's RMS (1 = the strongest taxel). Rejects wrong sizes,
/// decreasing or out-of-range indices and non-finite samples, naming the file.
VibrationMap loadTaxelWaveforms(const std::filesystem::path& dir, const TaxelWaveformOptions& options = {});

}  // namespace vt::haptics
