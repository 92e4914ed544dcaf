#include "modes/video_frames.hpp"

#include <cstdio>

#include "vt/core/error.hpp"
#include "vt/core/output_file.hpp"

namespace vt::app {

VideoFrameWriter::VideoFrameWriter(const net::LatestVideoFrame& frames, std::filesystem::path dir)
    : m_frames(frames), m_dir(std::move(dir)) {
  std::error_code ec;
  std::filesystem::create_directories(m_dir, ec);
  if (ec) fail("video output: cannot create folder '", m_dir.string(), "': ", ec.message());
}

int VideoFrameWriter::poll() {
  if (!m_frames.readNewer(m_frame, m_version)) return 0;
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06u.jpg", unsigned(m_frame.frameId));
  const std::filesystem::path path = m_dir / name;
  writeFileAtomically(path, {reinterpret_cast<const char*>(m_frame.jpeg.data()), m_frame.jpeg.size()});
  ++m_written;
  return 1;
}

}  // namespace vt::app
