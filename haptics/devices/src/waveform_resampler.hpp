#pragma once
// Turns the haptic loop's waveform blocks (8 kHz, one block per tick, arriving with the loop's
// jitter) into a continuous stream at an output device's rate: a small jitter buffer filled to
// `prefill` input samples before playing, linear interpolation between input samples, silence
// (counted) when input runs out, and the oldest input dropped (counted) when the buffer grows past
// twice the prefill, which bounds the latency when the loop's clock runs ahead of the device's.
// Allocates only at construction; used on one output thread.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "vt/haptics/actuator_frame.hpp"

namespace vt::haptics::detail {

class WaveformResampler {
 public:
  /// `channels[c]`: actuator played on output channel c (-1: silent). `prefill` in input samples.
  WaveformResampler(std::vector<int> channels, std::uint32_t outputRate_hz, int prefill);

  /// Appends one frame's block (a change of input rate restarts the stream).
  void push(const ActuatorFrame& frame) noexcept;
  /// Fills `out` (interleaved, out.size() / channels frames) with samples in -1..1.
  void render(std::span<float> out) noexcept;
  /// Forgets buffered input and waits for a new prefill (failsafe, restart).
  void reset() noexcept;

  std::size_t channels() const noexcept { return m_channels.size(); }
  std::uint64_t starvedFrames() const noexcept { return m_starved; }
  std::uint64_t skippedSamples() const noexcept { return m_skipped; }

 private:
  using Sample = std::array<float, kMaxActuators>;
  std::size_t size() const noexcept { return m_tail - m_head; }
  const Sample& at(std::size_t i) const noexcept { return m_fifo[(m_head + i) & kMask]; }

  static constexpr std::size_t kCapacity = 4096;  // 0.5 s at 8 kHz
  static constexpr std::size_t kMask = kCapacity - 1;
  std::vector<int> m_channels;
  std::uint32_t m_outputRate_hz;
  std::size_t m_prefill;
  std::vector<Sample> m_fifo;
  std::size_t m_head = 0, m_tail = 0;
  std::uint32_t m_inputRate_hz = 0;
  double m_step = 0.0, m_pos = 0.0;
  bool m_playing = false;
  bool m_started = false;  // played since the last reset
  std::uint64_t m_starved = 0, m_skipped = 0;
};

}  // namespace vt::haptics::detail
