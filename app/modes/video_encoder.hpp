#pragma once
// `--video FILE`: raw RGBA frames piped to an ffmpeg child process that encodes them (H.264 for
// .mp4) under a temporary name beside FILE, renamed into place once ffmpeg succeeded, so a failed
// run leaves no half video. The child is bounded like any input: a ffmpeg that stops reading (or
// stops writing its file after the last frame) for kStall_ms ends the run with a clear error, the
// stop request (Ctrl-C) ends the wait, and ffmpeg dies with this process (no orphan). Main thread.
#include <sys/types.h>

#include <cstdint>
#include <filesystem>

#include "vt/scene/image.hpp"

namespace vt::app {

/// The `ffmpeg` program on PATH, or empty.
std::filesystem::path findFfmpeg();

class VideoEncoder {
 public:
  /// How long ffmpeg may read nothing (or, at the end, write nothing) before it counts as stalled.
  static constexpr std::int64_t kStall_ms = 10'000;
  /// How long ffmpeg may take to finish its file once the stop request is set.
  static constexpr std::int64_t kStopGrace_ms = 2'000;

  /// Starts ffmpeg for `path` at `fps`; throws vt::Error ("`command`: --video ...") on failure.
  VideoEncoder(const std::filesystem::path& path, int width, int height, double fps, const char* command);
  /// An unfinished encoder (an error, a stop) kills and reaps ffmpeg and drops its partial file.
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  /// Sends one frame; throws vt::Error when ffmpeg exited or stalled. Returns early (the frame
  /// cut short, which ffmpeg drops) when the stop request is set.
  void write(const Image8& frame);
  /// Ends the input, waits for ffmpeg and moves the video into place; throws vt::Error naming
  /// what went wrong (ffmpeg's exit status, a stall, the stop request it did not finish within).
  void finish();

 private:
  [[noreturn]] void failAndKill(const std::string& why);
  void kill() noexcept;
  int waitExit(bool& stalled);

  std::filesystem::path m_path, m_partial;
  std::string m_command;
  int m_fd = -1;
  pid_t m_pid = -1;
};

}  // namespace vt::app
