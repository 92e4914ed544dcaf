#include "skinned_hands.hpp"

#include <cstddef>
#include <cstring>

#include "pipelines.hpp"
#include "shaders/hand_frag.h"
#include "shaders/skinned_hand_vert.h"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/renderer/vk_check.hpp"

namespace vt::renderer {
namespace {

/// Mirrors the vertex inputs of shaders/skinned_hand.vert.
struct SkinnedVertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::u8vec4 joints;
  glm::vec4 weights;
};

/// Mirrors the push constants of shaders/skinned_hand.vert.
struct HandConstants {
  glm::vec4 color;
  std::uint32_t firstJoint;
};

constexpr VkDeviceSize kJointBytes = sizeof(glm::mat4) * kHandJointCount * kMaxSkinnedHands;
constexpr VkMemoryPropertyFlags kHostMemory = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;

}  // namespace

SkinnedHands::SkinnedHands(const Device& device, VkDescriptorSetLayout frameLayout, std::uint32_t slots,
                           const HandMesh& right)
    : m_dev(device), m_device(device.device()) {
  const VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = 1;
  setInfo.pBindings = &binding;
  VT_VK(vkCreateDescriptorSetLayout(m_device, &setInfo, nullptr, &m_jointsLayout));
  const VkDescriptorSetLayout sets[2] = {frameLayout, m_jointsLayout};
  const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(HandConstants)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 2;
  layoutInfo.pSetLayouts = sets;
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &push;
  VT_VK(vkCreatePipelineLayout(m_device, &layoutInfo, nullptr, &m_layout));
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, slots};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = slots;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &size;
  VT_VK(vkCreateDescriptorPool(m_device, &poolInfo, nullptr, &m_pool));
  m_slots.resize(slots);
  for (Slot& slot : m_slots) {
    slot.joints = GpuBuffer(device, kJointBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, kHostMemory);
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = m_pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &m_jointsLayout;
    VT_VK(vkAllocateDescriptorSets(m_device, &alloc, &slot.set));
    const VkDescriptorBufferInfo bufferInfo{slot.joints.buffer, 0, kJointBytes};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = slot.set;
    write.dstBinding = 0;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    write.pBufferInfo = &bufferInfo;
    vkUpdateDescriptorSets(m_device, 1, &write, 0, nullptr);
  }
  setModel(right);
}

SkinnedHands::~SkinnedHands() {
  for (auto& [pass, pipeline] : m_pipelines) vkDestroyPipeline(m_device, pipeline, nullptr);
  m_slots.clear();
  if (m_pool) vkDestroyDescriptorPool(m_device, m_pool, nullptr);
  if (m_layout) vkDestroyPipelineLayout(m_device, m_layout, nullptr);
  if (m_jointsLayout) vkDestroyDescriptorSetLayout(m_device, m_jointsLayout, nullptr);
}

void SkinnedHands::setModel(const HandMesh& right) {
  validateHandMesh(right, "hand model");
  if (right.mesh.vertices.size() > budget::kSceneVertices / 2 || right.mesh.indices.size() > budget::kSceneIndices / 2) {
    fail("hand model: ", right.mesh.vertices.size(), " vertices and ", right.mesh.indices.size(),
         " indices exceed the renderer's limit");
  }
  const HandMesh left = mirrorHandMesh(right);
  std::vector<SkinnedVertex> vertices;
  std::vector<std::uint32_t> indices;
  for (const HandMesh* hand : {&right, &left}) {
    for (std::size_t v = 0; v < hand->mesh.vertices.size(); ++v) {
      const Vertex& src = hand->mesh.vertices[v];
      vertices.push_back({src.position, src.normal, hand->joints[v], hand->weights[v]});
    }
    indices.insert(indices.end(), hand->mesh.indices.begin(), hand->mesh.indices.end());
  }
  m_vertices = GpuBuffer(m_dev, vertices.size() * sizeof(SkinnedVertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, kHostMemory);
  m_indices = GpuBuffer(m_dev, indices.size() * sizeof(std::uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, kHostMemory);
  std::memcpy(m_vertices.mapped, vertices.data(), vertices.size() * sizeof(SkinnedVertex));
  std::memcpy(m_indices.mapped, indices.data(), indices.size() * sizeof(std::uint32_t));
  m_indexCount = std::uint32_t(right.mesh.indices.size());
  m_leftVertexOffset = std::int32_t(right.mesh.vertices.size());
  m_right = right;
  m_left = left;
}

void SkinnedHands::update(std::uint32_t slot, const std::vector<SkinnedHand>& hands) {
  auto* out = static_cast<glm::mat4*>(m_slots[slot].joints.mapped);
  for (std::size_t h = 0; h < hands.size(); ++h) {
    const auto matrices = skinningMatrices(hands[h].left ? m_left : m_right, hands[h].pose);
    std::memcpy(out + h * kHandJointCount, matrices.data(), sizeof(matrices));
  }
}

void SkinnedHands::record(VkCommandBuffer cmd, std::uint32_t slot, VkRenderPass renderPass, VkDescriptorSet frameSet,
                          std::uint32_t uniformOffset, const std::vector<SkinnedHand>& hands, bool depthOnly) {
  if (hands.empty()) return;
  VkPipeline pipeline = VK_NULL_HANDLE;
  for (const auto& [pass, p] : m_pipelines) {
    if (pass == renderPass) pipeline = p;
  }
  if (!pipeline) {
    const VkVertexInputBindingDescription binding{0, sizeof(SkinnedVertex), VK_VERTEX_INPUT_RATE_VERTEX};
    const VkVertexInputAttributeDescription attributes[4] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(SkinnedVertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(SkinnedVertex, normal)},
        {2, 0, VK_FORMAT_R8G8B8A8_UINT, offsetof(SkinnedVertex, joints)},
        {3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(SkinnedVertex, weights)}};
    PipelineStates states;
    states.vert = createShaderModule(m_device, kSkinnedHandVert);
    if (!depthOnly) states.frag = createShaderModule(m_device, kHandFrag);
    states.colorAttachments = depthOnly ? 0 : 1;
    states.bindings = {&binding, 1};
    states.attributes = attributes;
    states.cullMode = VK_CULL_MODE_BACK_BIT;
    states.depth.depthTestEnable = VK_TRUE;
    states.depth.depthWriteEnable = VK_TRUE;
    states.depth.depthCompareOp = VK_COMPARE_OP_LESS;
    try {
      pipeline = createGraphicsPipeline(m_device, m_layout, renderPass, states);
    } catch (...) {
      vkDestroyShaderModule(m_device, states.vert, nullptr);
      if (states.frag) vkDestroyShaderModule(m_device, states.frag, nullptr);
      throw;
    }
    vkDestroyShaderModule(m_device, states.vert, nullptr);
    if (states.frag) vkDestroyShaderModule(m_device, states.frag, nullptr);
    m_pipelines.emplace_back(renderPass, pipeline);
  }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  const VkDescriptorSet sets[2] = {frameSet, m_slots[slot].set};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m_layout, 0, 2, sets, 1, &uniformOffset);
  const VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &m_vertices.buffer, &zero);
  vkCmdBindIndexBuffer(cmd, m_indices.buffer, 0, VK_INDEX_TYPE_UINT32);
  for (std::size_t h = 0; h < hands.size(); ++h) {
    const HandConstants constants{hands[h].color, std::uint32_t(h * kHandJointCount)};
    vkCmdPushConstants(cmd, m_layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(constants), &constants);
    const bool left = hands[h].left;
    vkCmdDrawIndexed(cmd, m_indexCount, 1, left ? m_indexCount : 0, left ? m_leftVertexOffset : 0, 0);
  }
}

}  // namespace vt::renderer
