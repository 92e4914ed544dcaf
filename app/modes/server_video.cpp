#include "modes/server_video.hpp"

#include "modes/hand_control.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/renderer/device.hpp"
#include "vt/renderer/offscreen_target.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/scene/jpeg.hpp"

namespace vt::app {
namespace {

constexpr std::int64_t kIdlePoll_ns = 20'000'000;               // while no client wants video

}  // namespace

ServerVideo::ServerVideo(const LoadedScene& scene, const PoseHistory& poses, net::Server& server,
                         const ServerVideoOptions& options)
    : m_scene(scene), m_poses(poses), m_server(server), m_options(options) {
  if (m_options.width < 16 || m_options.width > 2048 || m_options.height < 16 || m_options.height > 2048)
    fail("server video: size ", m_options.width, "x", m_options.height, " not in 16..2048 a side");
  if (!(m_options.fps >= 1.0 && m_options.fps <= 60.0)) fail("server video: fps ", m_options.fps, " not in 1..60");
  if (m_options.quality < 1 || m_options.quality > 100) fail("server video: quality ", m_options.quality, " not in 1..100");
  // Created here so setup errors reach the caller; afterwards only the video thread uses them.
  m_device = renderer::Device::create({.validate = m_options.validate});
  m_renderer = std::make_unique<renderer::Renderer>(m_device);
  m_renderer->setScene(m_scene.scene);
  applyHandView(*m_renderer, m_options.hand);
  m_target = std::make_unique<renderer::OffscreenTarget>(m_device, std::uint32_t(m_options.width),
                                                         std::uint32_t(m_options.height));
  log::info("server video: ", m_options.width, "x", m_options.height, " JPEG q", m_options.quality, " at ",
            m_options.fps, " fps on ", m_device->description());
}

ServerVideo::~ServerVideo() {
  stop();
  if (m_renderer) m_renderer->waitIdle();
}

void ServerVideo::start() {
  if (m_running.exchange(true)) return;
  m_thread = std::thread([this] { run(); });
}

void ServerVideo::stop() noexcept {
  if (!m_running.exchange(false)) return;
  if (m_thread.joinable()) m_thread.join();
}

ServerVideoStats ServerVideo::stats() const noexcept {
  ServerVideoStats s;
  s.framesSent = m_sent.load();
  s.framesRendered = m_rendered.load();
  if (s.framesRendered > 0) {
    const double n = double(s.framesRendered);
    s.meanRender_ms = double(m_render_ns.load()) / n / 1e6;
    s.meanEncode_ms = double(m_encode_ns.load()) / n / 1e6;
    s.meanJpegBytes = double(m_bytes.load()) / n;
  }
  s.validationMessages = m_device->validationMessageCount();
  return s;
}

Image8 ServerVideo::renderFrame() {
  renderer::FrameDesc desc;
  desc.views = {m_scene.scene->camera.view(float(m_options.width) / float(m_options.height))};
  // The pose came over the network: its finger joints' orientations were derived from their
  // positions (net decodes them with orientJointsAlongBones), which the skinned hand needs.
  if (HandPose pose; m_poses.newest(pose) && pose.valid)
    renderer::appendHand(visualProxy(pose, *m_scene.haptic->collision), m_options.hand.style, desc);
  m_renderer->render(*m_target, desc);
  return m_target->readback();  // waits for this frame: one frame at a time
}

void ServerVideo::renderAndSend() {
  const Clock& clock = SteadyClock::instance();
  const std::int64_t t0 = clock.now_ns();
  const Image8 image = renderFrame();
  const std::int64_t t1 = clock.now_ns();
  const std::vector<std::uint8_t> jpeg = encodeJpeg(image, m_options.quality);
  const std::int64_t t2 = clock.now_ns();
  m_render_ns.fetch_add(std::uint64_t(t1 - t0), std::memory_order_relaxed);
  m_encode_ns.fetch_add(std::uint64_t(t2 - t1), std::memory_order_relaxed);
  m_bytes.fetch_add(jpeg.size(), std::memory_order_relaxed);
  m_rendered.fetch_add(1, std::memory_order_relaxed);
  if (m_server.sendVideo(jpeg, image.width, image.height)) m_sent.fetch_add(1, std::memory_order_relaxed);
}

void ServerVideo::run() noexcept {
  const Clock& clock = SteadyClock::instance();
  const std::int64_t period_ns = std::int64_t(1e9 / m_options.fps);
  std::int64_t next = clock.now_ns();
  while (m_running.load(std::memory_order_acquire)) {
    if (!m_server.videoWanted()) {
      clock.sleepUntil(clock.now_ns() + kIdlePoll_ns);
      next = clock.now_ns();
      continue;
    }
    try {
      renderAndSend();
    } catch (const std::exception& e) {
      // A lost device or a full disk of the log: the tactile session goes on without video.
      log::error("server video: ", e.what(), "; video stopped");
      return;
    }
    next += period_ns;
    const std::int64_t now = clock.now_ns();
    if (next < now) next = now;  // slower than the rate: no catch-up burst
    clock.sleepUntil(next);
  }
}

}  // namespace vt::app
