#pragma once
// The hand's shadow (internal): a depth-only pass draws the shadow casters (the hand) from the
// scene's directional light into one shadow map before the frame's render pass; the textured
// pass samples it with percentage-closer filtering (shaders/shadow.glsl). The light's
// orthographic frustum is fitted to the scene's bounds (the receivers: table and plates) and
// deepened towards the light to hold the casters. One map serves every frame slot: the pass's
// external dependency waits for the previous frame's fragment reads. Only the screen rectangle
// the casters' shadow can reach is drawn with the shadow-receiving pipeline.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "gpu.hpp"
#include "vt/renderer/frame.hpp"
#include "vt/scene/scene.hpp"

namespace vt::renderer {

/// The shadow part of the frame uniforms (mirrors the end of `Frame` in shaders/frame.glsl).
struct ShadowUniforms {
  glm::mat4 lightViewProj{1.0f};
  glm::vec4 shadow{0.0f};  // x: strength (0: no shadow this frame), y: PCF tap spacing (uv), z: depth bias
  glm::vec4 rect{0.0f};    // the map uv rectangle the casters' shadow can reach (min xy, max zw)
};

/// One frame's shadow: its uniforms and the corners of a world box the shadow can fall in (where
/// the lines along the light through the map rectangle it can reach cross the receivers' heights).
struct ShadowFrame {
  ShadowUniforms uniforms;
  std::array<glm::vec3, 8> reach{};
  bool active() const { return uniforms.shadow.x > 0.0f; }
};

/// The pixels of a view (one view, or both eyes for a multiview pass) that can see `reach`:
/// its projected bounds, widened by a pixel; the whole target when a corner is behind a camera;
/// an empty rectangle when it is off screen.
VkRect2D shadowScissor(const ShadowFrame& frame, std::span<const glm::mat4> viewProjs, VkExtent2D extent);

class ShadowPass {
 public:
  /// Shadow-map size (texels per side): ~1.4 mm per texel over the demo table.
  static constexpr std::uint32_t kMapSize = 1024;
  /// How much of the direct light a full shadow takes away.
  static constexpr float kStrength = 0.8f;

  /// Creates the map (left in DEPTH_STENCIL_READ_ONLY_OPTIMAL), its sampler, the depth-only render
  /// pass, framebuffer and the casters' pipeline. Throws vt::Error.
  ShadowPass(const Device& dev, VkPipelineLayout layout);
  ~ShadowPass();
  ShadowPass(const ShadowPass&) = delete;
  ShadowPass& operator=(const ShadowPass&) = delete;

  /// The map for set 0, binding 1 (comparison sampler, view, read-only layout).
  VkDescriptorImageInfo descriptor() const { return {m_sampler, m_map.view, kReadLayout}; }
  /// Fits the light to the scene's bounds and takes its light direction (null: no shadow).
  void setScene(const Scene* scene);
  /// The light and the reach of the casters' shadow for one frame; inactive (strength 0) when
  /// nothing casts or the shadow misses the scene (then the pass need not run).
  ShadowFrame frame(const std::vector<HandPrimitive>& casters) const;
  /// Begins the depth-only pass (map cleared, viewport set): bind the frame set at the copy
  /// whose viewProj is the light's, draw the casters with casterPipeline(), then end().
  void begin(VkCommandBuffer cmd) const;
  void end(VkCommandBuffer cmd) const { vkCmdEndRenderPass(cmd); }
  VkPipeline casterPipeline() const { return m_pipeline; }
  /// The depth-only pass, for casters that build their own pipelines (the skinned hands).
  VkRenderPass renderPass() const { return m_renderPass; }

 private:
  static constexpr VkImageLayout kReadLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  VkDevice m_device;
  GpuImage m_map;
  VkSampler m_sampler = VK_NULL_HANDLE;
  VkRenderPass m_renderPass = VK_NULL_HANDLE;
  VkFramebuffer m_framebuffer = VK_NULL_HANDLE;
  VkPipeline m_pipeline = VK_NULL_HANDLE;
  bool m_haveScene = false;
  glm::vec3 m_right{1, 0, 0}, m_up{0, 0, -1}, m_forward{0, -1, 0};  // light frame; forward: the light's travel
  glm::vec3 m_min{0.0f}, m_max{0.0f};  // the scene's bounds in the light frame (x, y, depth)
  std::vector<Aabb> m_objectBounds;    // each object's world bounds (the receivers)
  Aabb m_sceneBounds;                  // their union
};

}  // namespace vt::renderer
