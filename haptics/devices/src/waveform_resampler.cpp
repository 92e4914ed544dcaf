#include "waveform_resampler.hpp"

#include <algorithm>

namespace vt::haptics::detail {

WaveformResampler::WaveformResampler(std::vector<int> channels, std::uint32_t outputRate_hz, int prefill)
    : m_channels(std::move(channels)),
      m_outputRate_hz(outputRate_hz),
      m_prefill(std::size_t(std::clamp(prefill, 2, int(kCapacity / 4)))),
      m_fifo(kCapacity) {}

void WaveformResampler::reset() noexcept {
  m_head = m_tail = 0;
  m_pos = 0.0;
  m_playing = false;
  m_started = false;
}

void WaveformResampler::push(const ActuatorFrame& frame) noexcept {
  if (frame.blockLength == 0 || frame.sampleRate_hz == 0) return;
  if (frame.sampleRate_hz != m_inputRate_hz) {
    reset();
    m_inputRate_hz = frame.sampleRate_hz;
    m_step = double(m_inputRate_hz) / double(m_outputRate_hz);
  }
  const int length = std::min<int>(frame.blockLength, kMaxBlockSamples);
  for (int i = 0; i < length; ++i) {
    if (size() == kCapacity) {
      ++m_head;  // cannot happen within the latency bound below; kept safe anyway
      ++m_skipped;
    }
    Sample& s = m_fifo[m_tail++ & kMask];
    for (int a = 0; a < kMaxActuators; ++a) s[std::size_t(a)] = a < frame.actuatorCount ? frame.block[std::size_t(a)][std::size_t(i)] : 0.0f;
  }
  // Bound the latency: past twice the prefill, drop the oldest input down to the prefill.
  if (m_playing && size() > 2 * m_prefill) {
    const std::size_t drop = size() - m_prefill;
    m_head += drop;
    m_skipped += drop;
  }
}

void WaveformResampler::render(std::span<float> out) noexcept {
  const std::size_t channels = m_channels.size();
  for (std::size_t f = 0; f + channels <= out.size(); f += channels) {
    if (!m_playing && size() >= m_prefill) m_playing = m_started = true;
    if (m_playing && size() < 2) {
      m_playing = false;  // ran dry: play silence until the prefill is back
      m_pos = 0.0;
    }
    if (!m_playing) {
      if (m_started) ++m_starved;  // the first prefill is latency, not starvation
      std::fill_n(out.begin() + std::ptrdiff_t(f), channels, 0.0f);
      continue;
    }
    const Sample& a = at(0);
    const Sample& b = at(1);
    const float t = float(m_pos);
    for (std::size_t c = 0; c < channels; ++c) {
      const int actuator = m_channels[c];
      out[f + c] = actuator < 0 ? 0.0f : a[std::size_t(actuator)] + (b[std::size_t(actuator)] - a[std::size_t(actuator)]) * t;
    }
    m_pos += m_step;
    while (m_pos >= 1.0 && size() >= 2) {
      m_pos -= 1.0;
      ++m_head;
    }
  }
}

}  // namespace vt::haptics::detail
