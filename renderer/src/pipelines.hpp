#pragma once
// Render pass and graphics pipelines for one kind of target (colour format, view count, final
// layout, depth format and whether depth is kept). Built on first use of such a target, then
// reused every frame (internal).
#include <cstdint>

#include "vt/renderer/device.hpp"

namespace vt::renderer {

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
  VkDescriptorSetLayout frame = VK_NULL_HANDLE;     // set 0: per-frame uniforms
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
  VkPipeline overlay = VK_NULL_HANDLE;   // vibration heat colour, alpha-blended, no depth write
  VkPipeline hand = VK_NULL_HANDLE;      // instanced capsules
};

PassPipelines createPassPipelines(const Device& device, const Layouts& layouts, const PassKey& key);
void destroyPassPipelines(VkDevice device, PassPipelines& pass);

}  // namespace vt::renderer
