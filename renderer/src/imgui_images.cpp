#include "imgui_images.hpp"

#include <algorithm>
#include <cstring>

#include "pipelines.hpp"
#include "shaders/image_frag.h"
#include "shaders/image_vert.h"
#include "vt/core/error.hpp"
#include "vt/renderer/vk_check.hpp"

namespace vt::renderer {
namespace {

VkPipeline createPipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass renderPass) {
  // A quad from gl_VertexIndex (no vertex buffers), no depth test or culling, no blending.
  PipelineStates states;
  states.vert = createShaderModule(device, kImageVert);
  states.frag = createShaderModule(device, kImageFrag);
  states.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
  struct ModuleGuard {
    VkDevice device;
    const PipelineStates& states;
    ~ModuleGuard() {
      vkDestroyShaderModule(device, states.vert, nullptr);
      vkDestroyShaderModule(device, states.frag, nullptr);
    }
  } guard{device, states};
  return createGraphicsPipeline(device, layout, renderPass, states);
}

}  // namespace

ImGuiImages::ImGuiImages(Renderer& renderer, VkRenderPass renderPass)
    : m_renderer(renderer), m_device(renderer.device().device()) {
  VkSamplerCreateInfo samplerInfo{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  samplerInfo.magFilter = VK_FILTER_LINEAR;
  samplerInfo.minFilter = VK_FILTER_LINEAR;
  samplerInfo.addressModeU = samplerInfo.addressModeV = samplerInfo.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VT_VK(vkCreateSampler(m_device, &samplerInfo, nullptr, &m_sampler));
  VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = 1;
  setInfo.pBindings = &binding;
  VT_VK(vkCreateDescriptorSetLayout(m_device, &setInfo, nullptr, &m_setLayout));
  const VkDescriptorPoolSize poolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kSlots};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = kSlots;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &poolSize;
  VT_VK(vkCreateDescriptorPool(m_device, &poolInfo, nullptr, &m_pool));
  const VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(float) * 4};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &m_setLayout;
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &range;
  VT_VK(vkCreatePipelineLayout(m_device, &layoutInfo, nullptr, &m_layout));
  m_pipeline = createPipeline(m_device, m_layout, renderPass);
  for (Slot& slot : m_slots) {
    slot.owner = this;
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = m_pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &m_setLayout;
    VT_VK(vkAllocateDescriptorSets(m_device, &alloc, &slot.set));
  }
}

ImGuiImages::~ImGuiImages() {
  m_renderer.waitIdle();
  for (Slot& slot : m_slots) {
    slot.image.reset();
    slot.staging.reset();
  }
  vkDestroyPipeline(m_device, m_pipeline, nullptr);
  vkDestroyPipelineLayout(m_device, m_layout, nullptr);
  vkDestroyDescriptorPool(m_device, m_pool, nullptr);
  vkDestroyDescriptorSetLayout(m_device, m_setLayout, nullptr);
  vkDestroySampler(m_device, m_sampler, nullptr);
}

void ImGuiImages::set(std::uint32_t index, const Image8& rgba) {
  if (index >= kSlots) fail("imgui image: slot ", index, " not in 0..", kSlots - 1);
  if (rgba.channels != 4 || rgba.width < 1 || rgba.height < 1 || rgba.pixels.size() != std::size_t(rgba.width) * rgba.height * 4)
    fail("imgui image: expected a non-empty RGBA8 image, got ", rgba.width, "x", rgba.height, "x", rgba.channels);
  Slot& slot = m_slots[index];
  const Device& dev = m_renderer.device();
  const VkExtent2D extent{std::uint32_t(rgba.width), std::uint32_t(rgba.height)};
  const bool rebuild = !slot.ready || slot.image.spec.extent.width != extent.width || slot.image.spec.extent.height != extent.height;
  if (rebuild) {
    // Frames in flight may still sample the old image and its descriptor: let them finish.
    m_renderer.waitIdle();
    slot.ready = false;
    ImageSpec spec;
    spec.format = VK_FORMAT_R8G8B8A8_SRGB;
    spec.extent = extent;
    spec.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    slot.image = GpuImage(dev, spec, false);
    slot.staging = GpuBuffer(dev, rgba.pixels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                             VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    const VkDescriptorImageInfo imageInfo{m_sampler, slot.image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = slot.set;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    write.pImageInfo = &imageInfo;
    vkUpdateDescriptorSets(m_device, 1, &write, 0, nullptr);
  }
  std::memcpy(slot.staging.mapped, rgba.pixels.data(), rgba.pixels.size());
  // One queue: the barrier orders this copy after earlier frames that sample the image, and
  // submitOnce waits, so the staging buffer is free again and later frames see the new pixels.
  const VkImageLayout from = rebuild ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  submitOnce(dev, [&](VkCommandBuffer cmd) {
    transitionImage(cmd, slot.image.image, VK_IMAGE_ASPECT_COLOR_BIT, from, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, 1, 1);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyBufferToImage(cmd, slot.staging.buffer, slot.image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    transitionImage(cmd, slot.image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0, 1, 1);
  });
  slot.ready = true;
}

void ImGuiImages::draw(std::uint32_t index, float width_px, float height_px) {
  if (index >= kSlots) fail("imgui image: slot ", index, " not in 0..", kSlots - 1);
  Slot& slot = m_slots[index];
  slot.min = ImGui::GetCursorScreenPos();
  slot.max = {slot.min.x + width_px, slot.min.y + height_px};
  ImGui::Dummy({width_px, height_px});
  if (!slot.ready) return;
  ImDrawList* list = ImGui::GetWindowDrawList();
  list->AddCallback(&ImGuiImages::onDraw, &slot);
  list->AddCallback(ImDrawCallback_ResetRenderState, nullptr);  // ImGui's pipeline, set and buffers again
}

void ImGuiImages::onDraw(const ImDrawList*, const ImDrawCmd* command) {
  const Slot& slot = *static_cast<const Slot*>(command->UserCallbackData);
  const ImGuiImages& self = *slot.owner;
  const ImDrawData* data = ImGui::GetDrawData();
  if (!self.m_cmd || !data || data->DisplaySize.x <= 0 || data->DisplaySize.y <= 0) return;
  const ImVec2 scale = data->FramebufferScale;
  const float fbWidth = data->DisplaySize.x * scale.x, fbHeight = data->DisplaySize.y * scale.y;
  // The window's clip rectangle, in framebuffer pixels (as ImGui's backend computes it).
  const float x0 = std::max(0.0f, (command->ClipRect.x - data->DisplayPos.x) * scale.x);
  const float y0 = std::max(0.0f, (command->ClipRect.y - data->DisplayPos.y) * scale.y);
  const float x1 = std::min(fbWidth, (command->ClipRect.z - data->DisplayPos.x) * scale.x);
  const float y1 = std::min(fbHeight, (command->ClipRect.w - data->DisplayPos.y) * scale.y);
  if (x1 <= x0 || y1 <= y0) return;
  const VkViewport viewport{0.0f, 0.0f, fbWidth, fbHeight, 0.0f, 1.0f};
  const VkRect2D scissor{{std::int32_t(x0), std::int32_t(y0)}, {std::uint32_t(x1 - x0), std::uint32_t(y1 - y0)}};
  const float rect[4] = {(slot.min.x - data->DisplayPos.x) / data->DisplaySize.x * 2.0f - 1.0f,
                         (slot.min.y - data->DisplayPos.y) / data->DisplaySize.y * 2.0f - 1.0f,
                         (slot.max.x - slot.min.x) / data->DisplaySize.x * 2.0f,
                         (slot.max.y - slot.min.y) / data->DisplaySize.y * 2.0f};
  vkCmdBindPipeline(self.m_cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, self.m_pipeline);
  vkCmdBindDescriptorSets(self.m_cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, self.m_layout, 0, 1, &slot.set, 0, nullptr);
  vkCmdSetViewport(self.m_cmd, 0, 1, &viewport);
  vkCmdSetScissor(self.m_cmd, 0, 1, &scissor);
  vkCmdPushConstants(self.m_cmd, self.m_layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof rect, rect);
  vkCmdDraw(self.m_cmd, 4, 1, 0, 0);
}

}  // namespace vt::renderer
