#pragma once
// The server's video stream in an ImGui window of the desktop client (`vtouching client
// --video`): the newest complete JPEG frame the client received, decoded on the UI thread and
// uploaded into an ImGuiLayer image slot. Main thread only, between ImGuiLayer begin/endFrame.
#include <cstdint>
#include <string>

#include "vt/net/video_stream.hpp"
#include "vt/renderer/imgui_layer.hpp"

namespace vt::ui {

/// One "Server video" window. `imgui` and `frames` must outlive it.
class VideoWindow {
 public:
  VideoWindow(renderer::ImGuiLayer& imgui, const net::LatestVideoFrame& frames, std::uint32_t imageSlot = 0);
  /// Decodes the newest frame if one arrived, then draws the window (the last good frame, or a
  /// note while none came yet). A corrupt frame is counted and skipped.
  void draw();
  std::uint64_t framesShown() const noexcept { return m_shown; }
  std::uint64_t decodeFailures() const noexcept { return m_failures; }

 private:
  renderer::ImGuiLayer& m_imgui;
  const net::LatestVideoFrame& m_frames;
  std::uint32_t m_slot;
  net::VideoFrame m_frame;
  std::uint64_t m_version = 0;
  std::uint64_t m_shown = 0, m_failures = 0;
  int m_width = 0, m_height = 0;
  int m_sizedWidth = -1, m_sizedHeight = -1;  // the frame size the window was last fitted to
  std::string m_lastError;
};

}  // namespace vt::ui
