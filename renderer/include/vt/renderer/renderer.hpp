#pragma once
// The Vulkan renderer: uploads a vt::Scene once, then draws FrameDescs into any RenderTarget:
// lit textured meshes (depth-tested, sRGB-correct), an optional vibration-map overlay,
// skinned hand meshes or instanced hand primitives, and stereo through multiview. Double-buffered per-frame resources;
// steady-state frames allocate no Vulkan objects. Main (render) thread only.
#include <cstdint>
#include <functional>
#include <memory>

#include <vulkan/vulkan.h>

#include "vt/renderer/device.hpp"
#include "vt/renderer/frame.hpp"
#include "vt/renderer/render_target.hpp"
#include "vt/scene/hand_mesh.hpp"
#include "vt/scene/scene.hpp"

namespace vt::renderer {

/// Records extra commands inside the frame's render pass after the scene (e.g. Dear ImGui).
/// With per-view stereo it runs once per view's pass.
using PassHook = std::function<void(VkCommandBuffer)>;

/// How two views reach a two-layer target.
enum class StereoMode {
  Auto,       // multiview unless the device's multiview is unreliable (Device::multiviewReliable)
  Multiview,  // one render pass, both layers at once (VK_KHR_multiview, core in Vulkan 1.1)
  PerView,    // one render pass per layer, same pipelines and shaders
};

struct RendererOptions {
  StereoMode stereo = StereoMode::Auto;
};

class Renderer {
 public:
  /// Frames in flight (per-frame command buffers, uniforms and fences are this many).
  static constexpr std::uint32_t kFramesInFlight = 2;

  explicit Renderer(std::shared_ptr<Device> device, const RendererOptions& options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Uploads meshes, textures and vibration maps (waits for the GPU; not per frame).
  /// Throws vt::Error when the scene is invalid (Scene::validate) or too large.
  void setScene(std::shared_ptr<const Scene> scene);
  /// The mesh drawn for FrameDesc::hands, a right hand (left hands get its mirror); makeHandMesh()
  /// until called. Waits for the GPU; throws vt::Error when the mesh is invalid or too large.
  void setHandModel(const HandMesh& right);
  /// Draws one frame. False when the target skipped it (e.g. minimised window).
  /// Throws vt::Error when frame.views.size() != target.layers() or too many hands or hand primitives.
  bool render(RenderTarget& target, const FrameDesc& frame);
  /// Waits until the next frame can be drawn into `target` (a free frame slot, an image acquired:
  /// on a window this can block for tens of milliseconds), so that what it shows is read after
  /// the wait; the next render() into `target` draws into that image. False when the target has
  /// nothing to draw into now (render() then tries again).
  bool prepare(RenderTarget& target);
  /// Commands recorded in the render pass after the scene (frames with FrameDesc::ui); empty = none.
  void setPassHook(PassHook hook) { m_passHook = std::move(hook); }
  /// The render pass used for a target (for pipelines built outside, e.g. ImGui's).
  VkRenderPass renderPassFor(const RenderTarget& target);
  /// Blocks until every submitted frame finished.
  void waitIdle();
  const Device& device() const { return *m_device; }
  /// Whether two-view targets are drawn with multiview (else one pass per view).
  bool usesMultiview() const;
  /// Times GPU objects were built for a new target kind or target (pipelines, framebuffers,
  /// depth images); constant while the same targets are drawn (no per-frame allocation).
  std::uint64_t resourceBuilds() const;

 private:
  struct Impl;
  std::shared_ptr<Device> m_device;
  std::unique_ptr<Impl> m_impl;
  PassHook m_passHook;
};

}  // namespace vt::renderer
