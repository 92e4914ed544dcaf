#include "vt/haptics/devices/recorder.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "vt/core/error.hpp"
#include "vt/haptics/wav.hpp"

namespace vt::haptics {
namespace {

constexpr std::uint32_t kEmptyWavRate_hz = 8000;  // header rate when no waveform was recorded

void put(std::string& out, std::uint32_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(char((value >> (8 * i)) & 0xFF));  // RIFF is little-endian
}

// Appends a CSV field and its comma (shortest text that reads back to the same value).
template <class T>
void field(std::string& row, T value) {
  char text[32];
  row.append(text, std::to_chars(text, text + sizeof text, value).ptr);
  row.push_back(',');
}

}  // namespace

ActuatorRecorder::ActuatorRecorder(const std::filesystem::path& csvPath, const std::filesystem::path& wavPath,
                                   int channels)
    : m_channels(channels) {
  if (channels < 1 || channels > kMaxActuators) fail("recorder: channels must be 1..", kMaxActuators, ", got ", channels);
  if (!csvPath.empty()) {
    m_csv.emplace(csvPath);
    std::string header = "t_ns,sequence";
    for (int i = 0; i < channels; ++i) header += str(',', actuatorName(ActuatorId(i)));
    for (int i = 0; i < channels; ++i) header += str(',', actuatorName(ActuatorId(i)), "_hz");
    m_csv->write(header + '\n');
  }
  if (!wavPath.empty()) {
    m_wav.emplace(wavPath);
    m_wav->write(wavHeader());  // placeholder sizes, patched by finish()
  }
}

void ActuatorRecorder::record(const ActuatorFrame& frame) {
  if (m_finished) fail("recorder: record() after finish()");
  ++m_frames;
  if (m_csv) {
    m_row.clear();
    field(m_row, frame.t_ns);
    field(m_row, frame.sequence);
    for (int i = 0; i < m_channels; ++i) field(m_row, i < frame.actuatorCount ? frame.intensity[std::size_t(i)] : 0.0f);
    for (int i = 0; i < m_channels; ++i) field(m_row, i < frame.actuatorCount ? frame.frequency_hz[std::size_t(i)] : 0.0f);
    m_row.back() = '\n';
    m_csv->write(m_row);
  }
  const std::size_t length = std::min<std::size_t>(frame.blockLength, kMaxBlockSamples);
  if (!m_wav || length == 0 || frame.sampleRate_hz == 0) return;
  if (m_sampleRate_hz == 0) m_sampleRate_hz = frame.sampleRate_hz;
  if (frame.sampleRate_hz != m_sampleRate_hz) {
    ++m_rateMismatches;
    return;
  }
  m_row.clear();
  for (std::size_t s = 0; s < length; ++s) {
    for (int c = 0; c < m_channels; ++c) {
      const float v = c < frame.actuatorCount ? frame.block[std::size_t(c)][s] : 0.0f;
      const float clamped = std::isfinite(v) ? std::clamp(v, -1.0f, 1.0f) : 0.0f;
      put(m_row, std::uint32_t(std::uint16_t(wavSample(clamped))), 2);
    }
  }
  m_wav->write(m_row);
  m_wavSamples += length;
}

std::size_t ActuatorRecorder::drain(SpscRing<ActuatorFrame>& ring) {
  std::size_t n = 0;
  ActuatorFrame frame;
  while (ring.pop(frame)) {
    record(frame);
    ++n;
  }
  return n;
}

std::string ActuatorRecorder::wavHeader() const {
  try {
    return haptics::wavHeader(m_channels, m_sampleRate_hz ? m_sampleRate_hz : kEmptyWavRate_hz, m_wavSamples);
  } catch (const Error&) {
    fail(m_wav->path().string(), ": recording exceeds the 4 GiB WAV limit");
  }
}

void ActuatorRecorder::finish() {
  if (m_finished) return;
  m_finished = true;
  if (m_csv) m_csv->commit();
  if (m_wav) {
    const std::string header = wavHeader();
    m_wav->overwrite(0, header.data(), header.size());
    m_wav->commit();
  }
}

}  // namespace vt::haptics
