#pragma once
// A sink that records actuator frames for analysis: a CSV row per frame with each actuator's
// level and frequency, and a WAV file with one channel per actuator holding the frames'
// waveform blocks at the haptic sample rate. Both are written under temporary names and appear
// whole at finish() (vt::OutputFile). Runs on a recording thread, never the haptic one.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "vt/core/output_file.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/actuator_sink.hpp"

namespace vt::haptics {

class ActuatorRecorder final : public ActuatorSink {
 public:
  /// Opens both files (an empty path skips that file); throws vt::Error naming the file.
  /// record() throws vt::Error naming the file when a write fails (a full disk).
  ActuatorRecorder(const std::filesystem::path& csvPath, const std::filesystem::path& wavPath,
                   int channels = kMaxActuators);
  /// Without finish() (an error stopped the run) neither file appears.
  ~ActuatorRecorder() override = default;
  ActuatorRecorder(const ActuatorRecorder&) = delete;
  ActuatorRecorder& operator=(const ActuatorRecorder&) = delete;

  /// Recording thread: appends one frame. Frames whose sample rate differs from the first
  /// waveform frame's keep their CSV row but are left out of the WAV (and counted).
  void record(const ActuatorFrame& frame);
  /// Recording thread: records every frame queued in `ring` (its consumer); returns how many.
  std::size_t drain(SpscRing<ActuatorFrame>& ring);
  /// Writes the WAV header sizes and puts both files in place; throws vt::Error on I/O failure.
  void finish();
  /// ActuatorSink: the main thread records every frame; nothing is felt. stop() is finish().
  std::string name() const override { return "actuator recording"; }
  SinkThread thread() const override { return SinkThread::Main; }
  void deliver(const ActuatorFrame& frame) override { record(frame); }
  std::int64_t latency_ns() const override { return 0; }
  bool felt() const override { return false; }
  void stop() override { finish(); }

  /// Counters, recording thread: frames recorded, WAV samples per channel, frames left out of
  /// the WAV for a different sample rate, and the WAV's rate (0 until a waveform frame came).
  std::uint64_t frames() const noexcept { return m_frames; }
  std::uint64_t wavSamples() const noexcept { return m_wavSamples; }
  std::uint64_t rateMismatches() const noexcept { return m_rateMismatches; }
  std::uint32_t sampleRate_hz() const noexcept { return m_sampleRate_hz; }

 private:
  std::string wavHeader() const;

  std::optional<OutputFile> m_csv, m_wav;
  std::string m_row;  // one CSV row, reused
  int m_channels;
  std::uint32_t m_sampleRate_hz = 0;
  std::uint64_t m_frames = 0, m_wavSamples = 0, m_rateMismatches = 0;
  bool m_finished = false;
};

}  // namespace vt::haptics
