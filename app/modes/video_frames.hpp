#pragma once
// Headless video output of the client (`vtouching client --video-out DIR`): every new complete
// frame the client received is written as DIR/frame_<frameId>.jpg, exactly as it came and whole
// (vt::OutputFile: a full disk leaves no truncated frame).
#include <cstdint>
#include <filesystem>

#include "vt/net/video_stream.hpp"

namespace vt::app {

/// Writes newly received frames. Owner (main) thread only.
class VideoFrameWriter {
 public:
  /// Creates `dir` (throws vt::Error naming it when it cannot). `frames` must outlive this.
  VideoFrameWriter(const net::LatestVideoFrame& frames, std::filesystem::path dir);
  /// Writes the newest frame if one arrived since the last call (frames in between are
  /// skipped, as a display would). Returns 1 when one was written, else 0. Throws vt::Error on
  /// a write failure.
  int poll();
  std::uint64_t written() const noexcept { return m_written; }

 private:
  const net::LatestVideoFrame& m_frames;
  std::filesystem::path m_dir;
  net::VideoFrame m_frame;
  std::uint64_t m_version = 0;
  std::uint64_t m_written = 0;
};

}  // namespace vt::app
