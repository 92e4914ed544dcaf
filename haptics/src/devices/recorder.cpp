#include "vt/haptics/devices/recorder.hpp"

#include <algorithm>
#include <cmath>

#include "vt/core/error.hpp"
#include "vt/core/log.hpp"

namespace vt::haptics {
namespace {

constexpr std::uint32_t kEmptyWavRate_hz = 8000;  // header rate when no waveform was recorded
constexpr std::size_t kWavHeaderBytes = 44;

void put(std::ofstream& out, std::uint32_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.put(char((value >> (8 * i)) & 0xFF));  // RIFF is little-endian
}

}  // namespace

ActuatorRecorder::ActuatorRecorder(const std::filesystem::path& csvPath, const std::filesystem::path& wavPath,
                                   int channels)
    : m_csvPath(csvPath), m_wavPath(wavPath), m_channels(channels) {
  if (channels < 1 || channels > kMaxActuators) fail("recorder: channels must be 1..", kMaxActuators, ", got ", channels);
  if (!csvPath.empty()) {
    m_csv.open(csvPath);
    if (!m_csv) fail(csvPath.string(), ": cannot create the actuator CSV");
    m_csv << "t_ns,sequence";
    for (int i = 0; i < channels; ++i) m_csv << ',' << actuatorName(ActuatorId(i));
    for (int i = 0; i < channels; ++i) m_csv << ',' << actuatorName(ActuatorId(i)) << "_hz";
    m_csv << '\n';
  }
  if (!wavPath.empty()) {
    m_wav.open(wavPath, std::ios::binary);
    if (!m_wav) fail(wavPath.string(), ": cannot create the actuator WAV");
    writeWavHeader();  // placeholder sizes, patched by finish()
  }
}

ActuatorRecorder::~ActuatorRecorder() {
  try {
    finish();
  } catch (const Error& e) {
    log::error("recorder: ", e.what());
  }
}

void ActuatorRecorder::record(const ActuatorFrame& frame) {
  if (m_finished) fail("recorder: record() after finish()");
  ++m_frames;
  if (m_csv.is_open()) {
    m_csv << frame.t_ns << ',' << frame.sequence;
    for (int i = 0; i < m_channels; ++i) m_csv << ',' << (i < frame.actuatorCount ? frame.intensity[std::size_t(i)] : 0.0f);
    for (int i = 0; i < m_channels; ++i) m_csv << ',' << (i < frame.actuatorCount ? frame.frequency_hz[std::size_t(i)] : 0.0f);
    m_csv << '\n';
  }
  const std::size_t length = std::min<std::size_t>(frame.blockLength, kMaxBlockSamples);
  if (!m_wav.is_open() || length == 0 || frame.sampleRate_hz == 0) return;
  if (m_sampleRate_hz == 0) m_sampleRate_hz = frame.sampleRate_hz;
  if (frame.sampleRate_hz != m_sampleRate_hz) {
    ++m_rateMismatches;
    return;
  }
  for (std::size_t s = 0; s < length; ++s) {
    for (int c = 0; c < m_channels; ++c) {
      const float v = c < frame.actuatorCount ? frame.block[std::size_t(c)][s] : 0.0f;
      const float clamped = std::isfinite(v) ? std::clamp(v, -1.0f, 1.0f) : 0.0f;
      put(m_wav, std::uint32_t(std::uint16_t(std::int16_t(std::lround(clamped * 32767.0f)))), 2);
    }
  }
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

void ActuatorRecorder::writeWavHeader() {
  const std::uint32_t rate = m_sampleRate_hz ? m_sampleRate_hz : kEmptyWavRate_hz;
  const std::uint32_t blockAlign = std::uint32_t(m_channels) * 2;
  const std::uint64_t dataBytes = m_wavSamples * blockAlign;
  if (dataBytes > 0xFFFFFFFFull - kWavHeaderBytes) fail(m_wavPath.string(), ": recording exceeds the 4 GiB WAV limit");
  m_wav.write("RIFF", 4);
  put(m_wav, std::uint32_t(36 + dataBytes), 4);
  m_wav.write("WAVEfmt ", 8);
  put(m_wav, 16, 4);  // PCM fmt chunk size
  put(m_wav, 1, 2);   // PCM
  put(m_wav, std::uint32_t(m_channels), 2);
  put(m_wav, rate, 4);
  put(m_wav, rate * blockAlign, 4);
  put(m_wav, blockAlign, 2);
  put(m_wav, 16, 2);  // bits per sample
  m_wav.write("data", 4);
  put(m_wav, std::uint32_t(dataBytes), 4);
}

void ActuatorRecorder::finish() {
  if (m_finished) return;
  m_finished = true;
  if (m_csv.is_open()) {
    m_csv.close();
    if (!m_csv) fail(m_csvPath.string(), ": writing the actuator CSV failed");
  }
  if (m_wav.is_open()) {
    m_wav.seekp(0);
    writeWavHeader();
    m_wav.close();
    if (!m_wav) fail(m_wavPath.string(), ": writing the actuator WAV failed");
  }
}

}  // namespace vt::haptics
