#include "vt/haptics/files/clip_player.hpp"

#include <algorithm>
#include <cmath>

#include "vt/core/error.hpp"

namespace vt::haptics::files {

ClipPlayer::ClipPlayer(const HapticClip& clip, int tickRate_hz) : m_tickRate_hz(tickRate_hz) {
  if (tickRate_hz < 100 || tickRate_hz > 4000) fail("clip player: tick rate ", tickRate_hz, " Hz outside 100..4000");
  if (!(clip.duration_s >= 0.0 && clip.duration_s <= kMaxClip_s)) fail("clip player: clip of ", clip.duration_s, " s (at most ", kMaxClip_s, ")");
  // At most 8 samples a tick (8 kHz at 1 kHz): the glove plays levels, and 10 actuators x 10 min
  // of precomputed waveform stay under 200 MB.
  constexpr int kBlock = 8;
  const std::uint32_t own = clip.sampleRate_hz;
  const bool fits = own > 0 && own % std::uint32_t(tickRate_hz) == 0 && own / std::uint32_t(tickRate_hz) <= kBlock;
  m_rate_hz = fits ? own : std::uint32_t(kBlock * tickRate_hz);
  m_block = int(m_rate_hz / std::uint32_t(tickRate_hz));
  // Tick i plays [i, i+1) / tickRate: a clip of d seconds takes ceil(d * rate) ticks.
  m_ticks = std::max<std::uint64_t>(1, std::uint64_t(std::ceil(clip.duration_s * tickRate_hz - 1e-6)));
  const std::size_t samples = std::size_t(m_ticks) * std::size_t(m_block);
  for (const ClipChannel& c : clip.channels) {
    m_tracks.push_back({c.actuator, channelEnvelope(c, own), channelWaveform(c, own, m_rate_hz, samples)});
    m_actuatorCount = std::max<std::uint8_t>(m_actuatorCount, std::uint8_t(int(c.actuator) + 1));
  }
}

ActuatorFrame ClipPlayer::frame(std::uint64_t tick) const noexcept {
  ActuatorFrame frame = ActuatorFrame::silent(m_actuatorCount, std::int64_t(tick) * 1'000'000'000 / m_tickRate_hz);
  frame.sequence = tick;
  if (tick >= m_ticks) return frame;
  frame.blockLength = std::uint16_t(m_block);
  frame.sampleRate_hz = m_rate_hz;
  const double t_s = double(tick) / m_tickRate_hz;
  for (const Track& track : m_tracks) {
    const auto a = std::size_t(track.actuator);
    const EnvelopePoint p = envelopeAt(track.envelope, t_s);
    frame.intensity[a] = std::clamp(p.amplitude, 0.0f, 1.0f);
    frame.frequency_hz[a] = p.frequency_hz;
    for (int k = 0; k < m_block; ++k) frame.block[a][std::size_t(k)] = track.pcm[std::size_t(tick) * std::size_t(m_block) + std::size_t(k)];
  }
  return frame;
}

}  // namespace vt::haptics::files
