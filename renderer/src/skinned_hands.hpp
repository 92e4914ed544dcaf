#pragma once
// The skinned-hand pass (internal): the hand mesh (right, and its mirror for left hands) in
// host-visible buffers, a per-frame-slot uniform buffer of joint matrices, and one pipeline per
// render pass it is drawn in. Main (render) thread only.
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "gpu.hpp"
#include "vt/renderer/frame.hpp"
#include "vt/scene/hand_mesh.hpp"

namespace vt::renderer {

class SkinnedHands {
 public:
  /// frameLayout: set 0 (the frame uniforms, dynamic offset); `slots` frames in flight.
  SkinnedHands(const Device& device, VkDescriptorSetLayout frameLayout, std::uint32_t slots, const HandMesh& right);
  ~SkinnedHands();
  SkinnedHands(const SkinnedHands&) = delete;
  SkinnedHands& operator=(const SkinnedHands&) = delete;

  /// Replaces the mesh (the GPU must not be using the old one). Throws vt::Error if invalid.
  void setModel(const HandMesh& right);
  /// Writes the joint matrices of `hands` (at most kMaxSkinnedHands) for frame slot `slot`.
  void update(std::uint32_t slot, const std::vector<SkinnedHand>& hands);
  /// Draws `hands` inside `renderPass` (a pipeline is built on its first use); binds its own
  /// pipeline layout with `frameSet` at `uniformOffset` as set 0. `depthOnly`: the pass has no
  /// colour attachment (the shadow map), so the pipeline has no fragment stage.
  void record(VkCommandBuffer cmd, std::uint32_t slot, VkRenderPass renderPass, VkDescriptorSet frameSet,
              std::uint32_t uniformOffset, const std::vector<SkinnedHand>& hands, bool depthOnly = false);
  /// Pipelines built so far (one per render pass drawn in).
  std::uint64_t builds() const { return m_pipelines.size(); }

 private:
  struct Slot {
    GpuBuffer joints;
    VkDescriptorSet set = VK_NULL_HANDLE;
  };
  const Device& m_dev;
  VkDevice m_device;
  VkDescriptorSetLayout m_jointsLayout = VK_NULL_HANDLE;
  VkPipelineLayout m_layout = VK_NULL_HANDLE;
  VkDescriptorPool m_pool = VK_NULL_HANDLE;
  std::vector<Slot> m_slots;
  GpuBuffer m_vertices, m_indices;
  std::uint32_t m_indexCount = 0;      // per hand: right first, then left
  std::int32_t m_leftVertexOffset = 0;
  std::vector<std::pair<VkRenderPass, VkPipeline>> m_pipelines;
  HandMesh m_right, m_left;  // their inverse binds and pad radii give the joint matrices
};

}  // namespace vt::renderer
