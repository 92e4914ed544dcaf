#include "contact_rings.hpp"

#include <algorithm>

#include "pipelines.hpp"
#include "shaders/ring_frag.h"
#include "shaders/ring_vert.h"

namespace vt::renderer {
namespace {

/// Mirrors the per-instance attributes of shaders/ring.vert.
struct RingInstance {
  glm::vec4 centreRadius;
  glm::vec4 normalIntensity;
};

}  // namespace

VkPipeline createRingPipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass pass) {
  const VkShaderModule vert = createShaderModule(device, kRingVert);
  const VkShaderModule frag = createShaderModule(device, kRingFrag);
  struct ModuleGuard {
    VkDevice device;
    VkShaderModule vert, frag;
    ~ModuleGuard() {
      vkDestroyShaderModule(device, vert, nullptr);
      vkDestroyShaderModule(device, frag, nullptr);
    }
  } guard{device, vert, frag};
  const VkVertexInputBindingDescription binding{0, sizeof(RingInstance), VK_VERTEX_INPUT_RATE_INSTANCE};
  const VkVertexInputAttributeDescription attributes[2] = {
      {0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(RingInstance, centreRadius)},
      {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(RingInstance, normalIntensity)}};
  PipelineStates states;
  states.vert = vert;
  states.frag = frag;
  states.bindings = {&binding, 1};
  states.attributes = attributes;
  states.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
  states.depth.depthTestEnable = VK_TRUE;  // behind the hand, the hand hides the ring
  states.depth.depthWriteEnable = VK_FALSE;
  states.depth.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  states.blend = true;
  return createGraphicsPipeline(device, layout, pass, states);
}

ContactRings::ContactRings(const Device& dev, std::uint32_t slots) : m_counts(slots, 0) {
  const VkMemoryPropertyFlags hostMemory = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  for (std::uint32_t s = 0; s < slots; ++s) {
    m_buffers.emplace_back(dev, sizeof(RingInstance) * kMaxContactMarkers, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, hostMemory);
  }
}

void ContactRings::upload(std::uint32_t slot, const std::vector<ContactMarker>& markers) {
  auto* out = static_cast<RingInstance*>(m_buffers[slot].mapped);
  const auto count = std::uint32_t(std::min<std::size_t>(markers.size(), kMaxContactMarkers));
  for (std::uint32_t i = 0; i < count; ++i) {
    const ContactMarker& m = markers[i];
    const float intensity = std::clamp(m.intensity, 0.0f, 1.0f);
    const float radius = kRingRadiusMin_m + (kRingRadiusMax_m - kRingRadiusMin_m) * intensity;
    out[i] = {glm::vec4(m.position_m, radius), glm::vec4(m.normal, intensity)};
  }
  m_counts[slot] = count;
}

void ContactRings::draw(VkCommandBuffer cmd, std::uint32_t slot, VkPipeline pipeline) const {
  if (m_counts[slot] == 0) return;
  const VkDeviceSize zero = 0;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  vkCmdBindVertexBuffers(cmd, 0, 1, &m_buffers[slot].buffer, &zero);
  vkCmdDraw(cmd, 4, m_counts[slot], 0, 0);
}

}  // namespace vt::renderer
