#include "vt/haptics/vibration_map.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"

namespace vt::haptics {
namespace {

// Maps a continuous texel coordinate to an index, repeating or holding the border.
int texelIndex(int i, int size, bool wrap) noexcept {
  if (wrap) {
    const int m = i % size;
    return m < 0 ? m + size : m;
  }
  return std::clamp(i, 0, size - 1);
}

std::vector<std::uint8_t> readFile(const std::filesystem::path& path) {
  const std::string bytes = readInputFile(path, "waveforms", budget::kScanLogBytes);
  return {bytes.begin(), bytes.end()};
}

template <class T>
T readLittle(const std::uint8_t* p) noexcept {
  static_assert(std::endian::native == std::endian::little, "big-endian hosts would need a byte swap here");
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

// Linear resampling of one taxel's samples to `count` samples spanning the same duration.
void resample(std::span<const float> in, std::span<float> out) noexcept {
  if (in.empty()) {
    std::fill(out.begin(), out.end(), 0.0f);
    return;
  }
  const double step = double(in.size()) / double(out.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double x = std::max((double(i) + 0.5) * step - 0.5, 0.0);
    const auto i0 = std::min(std::size_t(x), in.size() - 1);
    const std::size_t i1 = std::min(i0 + 1, in.size() - 1);
    const float f = float(x - double(i0));
    out[i] = in[i0] + (in[i1] - in[i0]) * f;
  }
}

}  // namespace

VibrationMap::VibrationMap(ImageF intensity, std::string source, TaxelWaveforms waveforms)
    : m_intensity(std::move(intensity)), m_waveforms(std::move(waveforms)), m_source(std::move(source)) {
  if (m_intensity.channels != 1) fail(m_source, ": vibration map must have one channel, got ", m_intensity.channels);
  if (m_intensity.width <= 0 || m_intensity.height <= 0) fail(m_source, ": vibration map is empty");
  if (!m_waveforms.empty() &&
      m_waveforms.samples.size() != m_intensity.pixels.size() * std::size_t(m_waveforms.samplesPerTaxel)) {
    fail(m_source, ": waveform data does not match the map size");
  }
}

float VibrationMap::sample(glm::vec2 uv, bool wrap) const noexcept {
  if (m_intensity.empty() || !std::isfinite(uv.x) || !std::isfinite(uv.y)) return 0.0f;
  const int w = m_intensity.width, h = m_intensity.height;
  if (wrap) uv -= glm::floor(uv);  // keeps the float coordinates small far from the origin
  const float x = uv.x * float(w) - 0.5f;
  const float y = (1.0f - uv.y) * float(h) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  const int x0 = int(fx), y0 = int(fy);
  const int xa = texelIndex(x0, w, wrap), xb = texelIndex(x0 + 1, w, wrap);
  const int ya = texelIndex(y0, h, wrap), yb = texelIndex(y0 + 1, h, wrap);
  const float top = m_intensity.at(xa, ya) + (m_intensity.at(xb, ya) - m_intensity.at(xa, ya)) * tx;
  const float bottom = m_intensity.at(xa, yb) + (m_intensity.at(xb, yb) - m_intensity.at(xa, yb)) * tx;
  return top + (bottom - top) * ty;
}

glm::ivec2 VibrationMap::taxel(glm::vec2 uv, bool wrap) const noexcept {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return {0, 0};
  if (wrap) uv -= glm::floor(uv);
  const int w = m_intensity.width, h = m_intensity.height;
  return {texelIndex(int(std::floor(uv.x * float(w))), w, wrap), texelIndex(int(std::floor((1.0f - uv.y) * float(h))), h, wrap)};
}

std::span<const float> VibrationMap::waveform(glm::ivec2 taxel) const noexcept {
  if (m_waveforms.empty()) return {};
  const auto n = std::size_t(m_waveforms.samplesPerTaxel);
  const std::size_t index = std::size_t(taxel.y) * std::size_t(m_intensity.width) + std::size_t(taxel.x);
  return {m_waveforms.samples.data() + index * n, n};
}

VibrationMap loadVibrationMapPng(const std::filesystem::path& path) {
  return VibrationMap(loadChannelAsFloat(path, 0), path.string());
}

VibrationMap vibrationMapFromFloats(int width, int height, std::span<const float> values, const std::string& source) {
  if (width <= 0 || height <= 0) fail(source, ": map size ", width, "x", height, " must be positive");
  if (values.size() != std::size_t(width) * std::size_t(height)) {
    fail(source, ": ", values.size(), " values for a ", width, "x", height, " map");
  }
  ImageF image(width, height, 1);
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) fail(source, ": value ", i, " is not finite");
    image.pixels[i] = std::clamp(values[i], 0.0f, 1.0f);
  }
  return VibrationMap(std::move(image), source);
}

VibrationMap loadTaxelWaveforms(const std::filesystem::path& dir, const TaxelWaveformOptions& options) {
  const std::filesystem::path headerPath = dir / "header.bin", dataPath = dir / "data.bin";
  const std::string hp = headerPath.string(), dp = dataPath.string();
  if (options.samplesPerTaxel < 1 || options.samplesPerTaxel > 65536) {
    fail(dir.string(), ": samplesPerTaxel ", options.samplesPerTaxel, " out of range 1..65536");
  }
  const std::vector<std::uint8_t> header = readFile(headerPath);
  if (header.size() < 8) fail(hp, ": ", header.size(), " bytes, too short for height and width");
  const auto height = readLittle<std::int32_t>(header.data()), width = readLittle<std::int32_t>(header.data() + 4);
  if (height <= 0 || width <= 0 || height > 16384 || width > 16384) {
    fail(hp, ": height ", height, " x width ", width, " out of range 1..16384");
  }
  const std::size_t taxels = std::size_t(height) * std::size_t(width);
  if (header.size() != 8 + 4 * taxels) {
    fail(hp, ": ", header.size(), " bytes, expected ", 8 + 4 * taxels, " for ", height, "x", width, " start indices");
  }
  const std::vector<std::uint8_t> dataBytes = readFile(dataPath);
  if (dataBytes.size() % 4 != 0) fail(dp, ": ", dataBytes.size(), " bytes is not a whole number of float32 samples");
  const std::size_t count = dataBytes.size() / 4;
  std::vector<float> data(count);
  for (std::size_t i = 0; i < count; ++i) {
    data[i] = readLittle<float>(dataBytes.data() + 4 * i);
    if (!std::isfinite(data[i])) fail(dp, ": sample ", i, " is not finite");
    data[i] -= 1.0f;  // remove gravity: the accelerometer rests at 1 g
  }
  std::vector<std::size_t> starts(taxels + 1, count);
  for (std::size_t i = 0; i < taxels; ++i) {
    const auto s = readLittle<std::int32_t>(header.data() + 8 + 4 * i);
    if (s < 0 || std::size_t(s) > count) fail(hp, ": start index ", i, " = ", s, " outside data.bin's ", count, " samples");
    if (i > 0 && std::size_t(s) < starts[i - 1]) {
      fail(hp, ": start index ", i, " = ", s, " decreases (previous ", starts[i - 1], ")");
    }
    starts[i] = std::size_t(s);
  }
  TaxelWaveforms waves;
  waves.samplesPerTaxel = options.samplesPerTaxel;
  waves.samples.resize(taxels * std::size_t(options.samplesPerTaxel));
  ImageF intensity(width, height, 1);
  float peak = 0.0f, maxRms = 0.0f;
  for (std::size_t i = 0; i < taxels; ++i) {
    const std::span<const float> in(data.data() + starts[i], starts[i + 1] - starts[i]);
    const std::span<float> out(waves.samples.data() + i * std::size_t(options.samplesPerTaxel),
                               std::size_t(options.samplesPerTaxel));
    resample(in, out);
    double energy = 0.0;
    for (float s : out) {
      peak = std::max(peak, std::abs(s));
      energy += double(s) * s;
    }
    intensity.pixels[i] = float(std::sqrt(energy / double(out.size())));
    maxRms = std::max(maxRms, intensity.pixels[i]);
  }
  waves.peak_g = peak;
  if (peak > 0.0f) for (float& s : waves.samples) s /= peak;
  if (maxRms > 0.0f) for (float& v : intensity.pixels) v /= maxRms;
  return VibrationMap(std::move(intensity), dir.string(), std::move(waves));
}

}  // namespace vt::haptics
