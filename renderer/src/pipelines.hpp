#pragma once
// Render pass and graphics pipelines for one kind of target (colour format, view count, final
// layout, depth format and whether depth is kept). Built on first use of such a target, then
// reused every frame (internal).
#include <cstdint>
#include <span>

#include "vt/renderer/device.hpp"
#include "vt/renderer/vk_check.hpp"

namespace vt::renderer {

/// A shader module from embedded SPIR-V (the caller destroys it). Throws vt::Error.
template <std::size_t N>
VkShaderModule createShaderModule(VkDevice device, const std::uint32_t (&code)[N]) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = sizeof(code);
  info.pCode = code;
  VkShaderModule module = VK_NULL_HANDLE;
  VT_VK(vkCreateShaderModule(device, &info, nullptr, &module));
  return module;
}

/// What differs between our graphics pipelines; the rest is shared: dynamic viewport and
/// scissor, one sample, one colour attachment (alpha blending when `blend`), or none for a
/// depth-only pass (then `frag` may be null).
struct PipelineStates {
  VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
  std::span<const VkVertexInputBindingDescription> bindings;  // empty: no vertex input
  std::span<const VkVertexInputAttributeDescription> attributes;
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkCullModeFlags cullMode = VK_CULL_MODE_NONE;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  bool blend = false;
  std::uint32_t colorAttachments = 1;  // 0: depth only
  const VkSpecializationInfo* fragSpecialization = nullptr;
};

/// One graphics pipeline in `pass` (the shader modules stay the caller's). Throws vt::Error.
VkPipeline createGraphicsPipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass pass,
                                  const PipelineStates& states);

struct PassKey {
  VkFormat colorFormat = VK_FORMAT_UNDEFINED;
  std::uint32_t views = 1;  // multiview with this many layers (1 = plain single-layer pass)
  VkImageLayout finalLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  bool storeDepth = false;  // the target's own depth images (a compositor reads them): STORE, not DONT_CARE
  bool operator==(const PassKey&) const = default;
};

/// Descriptor set and pipeline layouts shared by every pass.
struct Layouts {
  VkDescriptorSetLayout frame = VK_NULL_HANDLE;     // set 0: per-frame uniforms + the hand's shadow map
  VkDescriptorSetLayout material = VK_NULL_HANDLE;  // set 1: albedo + vibration map
  VkPipelineLayout pipeline = VK_NULL_HANDLE;       // both sets + ObjectConstants push range
};

Layouts createLayouts(VkDevice device);
void destroyLayouts(VkDevice device, Layouts& layouts);

/// One render pass and the pipelines drawn inside it.
struct PassPipelines {
  PassKey key;
  VkRenderPass renderPass = VK_NULL_HANDLE;
  VkPipeline textured = VK_NULL_HANDLE;  // lit textured meshes
  VkPipeline texturedShadowed = VK_NULL_HANDLE;  // the same, receiving the hand's shadow
  VkPipeline overlay = VK_NULL_HANDLE;   // vibration heat colour, alpha-blended, no depth write
  VkPipeline hand = VK_NULL_HANDLE;      // instanced capsules
  VkPipeline rings = VK_NULL_HANDLE;     // contact markers, alpha-blended, no depth write
};

PassPipelines createPassPipelines(const Device& device, const Layouts& layouts, const PassKey& key);
void destroyPassPipelines(VkDevice device, PassPipelines& pass);

/// The hand drawn depth-only into `depthOnlyPass` (the shadow map): the hand pipeline's vertex
/// stage and inputs, no fragment stage. Throws vt::Error.
VkPipeline createHandShadowPipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass depthOnlyPass);

}  // namespace vt::renderer
