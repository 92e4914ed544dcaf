#pragma once
// The server's virtual camera, as in the paper's reference app: the scene from its default
// camera plus the mirror hand (the newest pose the server applied), rendered offscreen at a
// fixed rate on its own thread, JPEG-encoded and handed to net::Server, which sends it to a
// client that asked for video. It renders nothing while no such client is connected.
#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>

#include "modes/hand_view.hpp"
#include "modes/scene_source.hpp"
#include "vt/core/latest_value.hpp"
#include "vt/net/server.hpp"
#include "vt/scene/hand.hpp"
#include "vt/scene/image.hpp"
#include "vt/scene/pose_history.hpp"

namespace vt::renderer {
class Device;
class Renderer;
class OffscreenTarget;
}  // namespace vt::renderer

namespace vt::app {

/// Video settings (`vtouching serve --video [--video-fps N] [--video-quality Q]`).
struct ServerVideoOptions {
  int width = 480;     // the reference app's 480x480
  int height = 480;
  double fps = 15.0;   // 1..60
  int quality = 75;    // JPEG quality 1..100
  bool validate = false;  // Vulkan validation layer (tests)
  HandViewOptions hand;   // --hand, --hand-model
};

/// Counters; a snapshot is safe from any thread.
struct ServerVideoStats {
  std::uint64_t framesSent = 0;
  std::uint64_t framesRendered = 0;
  double meanRender_ms = 0.0;  // render + GPU readback
  double meanEncode_ms = 0.0;
  double meanJpegBytes = 0.0;
  std::uint64_t validationMessages = 0;
};

/// Owns an offscreen renderer and the video thread. Construct/start/stop on the owner thread.
class ServerVideo {
 public:
  /// Creates the Vulkan device, uploads the scene and the target (throws vt::Error naming the
  /// problem). `poses` and `server` must outlive this object.
  ServerVideo(const LoadedScene& scene, const PoseHistory& poses, net::Server& server,
              const ServerVideoOptions& options = {});
  ~ServerVideo();
  ServerVideo(const ServerVideo&) = delete;
  ServerVideo& operator=(const ServerVideo&) = delete;

  /// Starts the video thread. Owner thread.
  void start();
  /// Joins the video thread. Owner thread; idempotent.
  void stop() noexcept;
  ServerVideoStats stats() const noexcept;
  /// The frame the video sends next (before JPEG): the scene and the newest mirror hand. The
  /// video thread's own step; the owner may call it while that thread is not running (tests).
  Image8 renderFrame();

 private:
  void run() noexcept;
  void renderAndSend();

  LoadedScene m_scene;
  const PoseHistory& m_poses;
  net::Server& m_server;
  ServerVideoOptions m_options;
  std::shared_ptr<renderer::Device> m_device;
  std::unique_ptr<renderer::Renderer> m_renderer;
  std::unique_ptr<renderer::OffscreenTarget> m_target;
  std::atomic<bool> m_running{false};
  std::atomic<std::uint64_t> m_sent{0}, m_rendered{0}, m_render_ns{0}, m_encode_ns{0}, m_bytes{0};
  std::thread m_thread;
};

}  // namespace vt::app
