#include "ui/video_window.hpp"

#include <algorithm>

#include <imgui.h>

#include "ui/hud_layout.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/jpeg.hpp"

namespace vt::ui {

VideoWindow::VideoWindow(renderer::ImGuiLayer& imgui, const net::LatestVideoFrame& frames, std::uint32_t imageSlot)
    : m_imgui(imgui), m_frames(frames), m_slot(imageSlot) {
  installHudLayout();
}

void VideoWindow::draw() {
  if (m_frames.readNewer(m_frame, m_version)) {
    try {
      const Image8 image = decodeJpeg(m_frame.jpeg, "video frame " + std::to_string(m_frame.frameId));
      m_imgui.setImage(m_slot, image);
      m_width = image.width;
      m_height = image.height;
      ++m_shown;
    } catch (const Error& e) {  // a corrupt frame: keep showing the last good one
      ++m_failures;
      m_lastError = e.what();
    }
  }
  // The window fits a new frame size once, at most 35 % of the display's height so the local
  // view and the hand in its middle stay visible; it is docked in the bottom-right corner until
  // the user moves it, and may be resized.
  if (m_width != m_sizedWidth || m_height != m_sizedHeight) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float scale = m_height > 0 ? std::min(1.0f, 0.35f * display.y / float(m_height)) : 1.0f;
    const bool none = m_width == 0;
    ImGui::SetNextWindowSize({none ? 320.0f : scale * float(m_width) + 16.0f, none ? 80.0f : scale * float(m_height) + 60.0f});
    m_sizedWidth = m_width;
    m_sizedHeight = m_height;
  }
  dockNextPanel("Server video", DockCorner::BottomRight);
  const bool open = ImGui::Begin("Server video");
  endDockedPanel();
  if (open) {
    if (m_shown == 0) {
      ImGui::TextUnformatted("waiting for the server's video stream...");
    } else {
      // Fit the window's width, keeping the frame's aspect ratio.
      const float width = std::max(16.0f, ImGui::GetContentRegionAvail().x);
      m_imgui.image(m_slot, width, width * float(m_height) / float(m_width));
      ImGui::Text("frame %u, %d x %d, %zu bytes", unsigned(m_frame.frameId), m_width, m_height, m_frame.jpeg.size());
    }
    if (m_failures > 0) ImGui::Text("%llu corrupt frames (%s)", (unsigned long long)m_failures, m_lastError.c_str());
  }
  ImGui::End();
}

}  // namespace vt::ui
