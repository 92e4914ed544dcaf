#pragma once
// Replayable recordings (`--record FILE`) and their deterministic replay (`vtouching replay`).
// Text, one record per line (format in docs/app.md): the scene and haptic settings, then
// timestamped poses (P), contacts (C), actuator frames (F) and displayed frames (D), and an end
// record (E) with the line count and a checksum, without which replay refuses the file (a
// truncated recording).
// Floats are written with 9 significant digits, so every value reads back bit-exact.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <istream>
#include <memory>
#include <string>
#include <string_view>

#include "modes/consistency_meter.hpp"
#include "modes/haptic_options.hpp"
#include "modes/scene_source.hpp"
#include "vt/core/output_file.hpp"
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/actuator_sink.hpp"
#include "vt/haptics/haptic_loop.hpp"
#include "vt/scene/hand.hpp"

namespace vt::app {

class TouchPipeline;

inline constexpr const char* kRecordingMagic = "vtouching-recording 3";

/// FNV-1a 64 of `bytes`, continuing from `hash` (the end record's checksum covers every byte
/// before the end line).
std::uint64_t recordingChecksum(std::string_view bytes, std::uint64_t hash = 0xcbf29ce484222325ull) noexcept;

/// Writes a recording. Main thread only (it is fed from the rings the main thread drains): an
/// actuator sink for the frames, and the touch pipeline hands it the poses, traces and frames drawn.
class ReplayRecorder final : public haptics::ActuatorSink {
 public:
  /// Creates the file (under a temporary name until finish()) and writes the header; throws
  /// vt::Error naming the file.
  ReplayRecorder(const std::filesystem::path& path, const SceneOptions& scene, const HapticOptions& haptic);
  /// A new haptic-loop segment (settings changed; the loop restarted with fresh state).
  void config(const HapticOptions& haptic);
  /// Marks a client's recording: its frames came from the server at `server`, so there is no
  /// loop to replay (replay refuses it); its records are the consistency meter's inputs.
  void remote(std::string_view server);
  /// A pose as the input published it; `jump`: it began a new pose-history segment (a reset
  /// or teleport: the replay must not sweep across it either).
  void pose(const HandPose& pose, bool jump);
  void contact(const haptics::ContactTrace& trace);
  /// A displayed frame: its display time, the drawn hand's time and its first `contacts` tips.
  void drawn(const DrawnFrame& frame, std::size_t contacts);
  void frame(const haptics::ActuatorFrame& frame);
  /// Writes the end record, closes and renames the file into place; throws vt::Error on I/O
  /// failure (then no file is left behind). Idempotent.
  void finish();
  std::uint64_t frames() const { return m_frames; }
  /// ActuatorSink: every frame on the main thread; nothing is felt; stop() is finish().
  std::string name() const override { return "replay recording"; }
  haptics::SinkThread thread() const override { return haptics::SinkThread::Main; }
  void deliver(const haptics::ActuatorFrame& f) override { frame(f); }
  std::int64_t latency_ns() const override { return 0; }
  bool felt() const override { return false; }
  void stop() override { finish(); }
  const std::filesystem::path& path() const { return m_path; }

 private:
  void line(std::string_view text);

  std::filesystem::path m_path;
  std::unique_ptr<OutputFile> m_out;
  std::uint64_t m_frames = 0, m_lines = 0, m_checksum = recordingChecksum({});
  bool m_finished = false;
};

struct ReplayResult {
  std::uint64_t frames = 0;       // actuator frames replayed
  std::uint64_t mismatches = 0;   // frames whose output differs from the recording
  double maxDifference = 0.0;     // largest |replayed - recorded| intensity
  std::uint64_t poses = 0, contacts = 0;
};

/// What a replay shows besides the comparison (`vtouching replay --out DIR`).
struct ReplayObserver {
  /// The replay's pipeline was made (at the recording's first config line).
  std::function<void(const LoadedScene& scene, TouchPipeline& pipeline)> started;
  /// After each replayed tick (drained) at the recording's `t_ns`.
  std::function<void(std::int64_t t_ns, TouchPipeline& pipeline)> ticked;
};

/// Where a replay gets the scene a recording names (the fuzz target's is loaded once).
using SceneLoader = std::function<LoadedScene(const SceneOptions&)>;

/// Re-runs the recorded poses through a fresh stepped touch pipeline (each recorded tick at its
/// recorded time, after the poses the live history held then) and compares each actuator frame
/// with the recorded one. `outCsv` (optional) receives the
/// replayed frames; `observer` (optional) sees the pipeline and every tick. Throws vt::Error
/// naming the file and line on malformed input.
ReplayResult replayRecording(const std::filesystem::path& path, const std::filesystem::path& outCsv = {},
                             const ReplayObserver& observer = {});
/// The same from a stream (`name` in its errors), with the scene from `load`.
ReplayResult replayRecording(std::istream& in, const std::string& name, const SceneLoader& load,
                             const std::filesystem::path& outCsv = {}, const ReplayObserver& observer = {});

}  // namespace vt::app
