#include "pipelines.hpp"

#include <array>
#include <cstddef>
#include <vector>

#include "contact_rings.hpp"
#include "gpu_scene.hpp"
#include "shaders/hand_frag.h"
#include "shaders/hand_vert.h"
#include "shaders/mesh_frag.h"
#include "shaders/mesh_vert.h"
#include "shaders/overlay_frag.h"
#include "vt/renderer/frame.hpp"
#include "vt/renderer/vk_check.hpp"

namespace vt::renderer {
namespace {

VkRenderPass createRenderPass(const Device& dev, const PassKey& key) {
  const VkAttachmentDescription attachments[2] = {
      {0, key.colorFormat, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE,
       VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_DONT_CARE, VK_IMAGE_LAYOUT_UNDEFINED, key.finalLayout},
      {0, key.depthFormat, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR,
       key.storeDepth ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE,
       VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_DONT_CARE, VK_IMAGE_LAYOUT_UNDEFINED,
       VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL}};
  const VkAttachmentReference color{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference depth{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &color;
  subpass.pDepthStencilAttachment = &depth;
  // In: wait for earlier use of the attachments (and a window's acquire semaphore, which waits at
  // colour output). Out: make the colour (and stored depth) visible to a following copy
  // (offscreen readback, a runtime's compositor or capture).
  const VkPipelineStageFlags attachmentStages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                                VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                                VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  const VkAccessFlags attachmentWrites = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  const VkSubpassDependency dependencies[2] = {
      {VK_SUBPASS_EXTERNAL, 0, attachmentStages, attachmentStages, attachmentWrites,
       attachmentWrites | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT, 0},
      {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
       VK_PIPELINE_STAGE_TRANSFER_BIT, attachmentWrites, VK_ACCESS_TRANSFER_READ_BIT, 0}};
  const std::uint32_t viewMask = (1u << key.views) - 1u;
  VkRenderPassMultiviewCreateInfo multiview{VK_STRUCTURE_TYPE_RENDER_PASS_MULTIVIEW_CREATE_INFO};
  multiview.subpassCount = 1;
  multiview.pViewMasks = &viewMask;
  multiview.correlationMaskCount = 1;
  multiview.pCorrelationMasks = &viewMask;  // the eyes see nearly the same thing
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.pNext = key.views > 1 ? &multiview : nullptr;
  info.attachmentCount = 2;
  info.pAttachments = attachments;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = dependencies;
  VkRenderPass pass = VK_NULL_HANDLE;
  VT_VK(vkCreateRenderPass(dev.device(), &info, nullptr, &pass));
  return pass;
}

struct PipelineSpec {
  VkShaderModule vert, frag;
  bool instanced;   // hand: per-instance attributes at binding 1
  bool blend;       // overlay: alpha blending, depth test <=, no depth write
  bool depthOnly = false;  // shadow map: no colour attachment, no fragment stage
  bool receivesShadow = false;  // mesh.frag's kReceivesShadow
};

VkPipeline createPipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass pass, const PipelineSpec& spec) {
  const VkVertexInputBindingDescription bindings[2] = {
      {0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX},
      {1, sizeof(glm::vec4) * 3, VK_VERTEX_INPUT_RATE_INSTANCE}};
  std::vector<VkVertexInputAttributeDescription> attributes = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)}};
  if (spec.instanced) {
    for (std::uint32_t i = 0; i < 3; ++i) attributes.push_back({3 + i, 1, VK_FORMAT_R32G32B32A32_SFLOAT, i * 16});
  } else {
    attributes.push_back({2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)});
  }
  PipelineStates states;
  states.vert = spec.vert;
  states.frag = spec.frag;
  states.bindings = {bindings, spec.instanced ? 2u : 1u};
  states.attributes = attributes;
  states.cullMode = VK_CULL_MODE_BACK_BIT;
  states.depth.depthTestEnable = VK_TRUE;
  states.depth.depthWriteEnable = spec.blend ? VK_FALSE : VK_TRUE;
  states.depth.depthCompareOp = spec.blend ? VK_COMPARE_OP_LESS_OR_EQUAL : VK_COMPARE_OP_LESS;
  states.blend = spec.blend;
  states.colorAttachments = spec.depthOnly ? 0 : 1;
  const VkBool32 receivesShadow = VK_TRUE;
  const VkSpecializationMapEntry entry{0, 0, sizeof(VkBool32)};
  const VkSpecializationInfo specialization{1, &entry, sizeof(VkBool32), &receivesShadow};
  if (spec.receivesShadow) states.fragSpecialization = &specialization;
  return createGraphicsPipeline(device, layout, pass, states);
}

}  // namespace

VkPipeline createGraphicsPipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass pass,
                                  const PipelineStates& states) {
  const VkPipelineShaderStageCreateInfo stages[2] = {
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, states.vert, "main", nullptr},
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, states.frag, "main",
       states.fragSpecialization}};
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vertexInput.vertexBindingDescriptionCount = std::uint32_t(states.bindings.size());
  vertexInput.pVertexBindingDescriptions = states.bindings.data();
  vertexInput.vertexAttributeDescriptionCount = std::uint32_t(states.attributes.size());
  vertexInput.pVertexAttributeDescriptions = states.attributes.data();
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = states.topology;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = states.cullMode;
  // The projection flips Y, so triangles counter-clockwise seen from outside stay so on screen.
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineColorBlendAttachmentState blend{};
  blend.blendEnable = states.blend ? VK_TRUE : VK_FALSE;
  blend.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
  blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
  blend.colorBlendOp = VK_BLEND_OP_ADD;
  blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
  blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
  blend.alphaBlendOp = VK_BLEND_OP_ADD;
  blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                         VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo colorBlend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  colorBlend.attachmentCount = states.colorAttachments;
  colorBlend.pAttachments = &blend;
  const VkDynamicState dynamicStates[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamicStates;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = states.frag ? 2 : 1;
  info.pStages = stages;
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &states.depth;
  info.pColorBlendState = &colorBlend;
  info.pDynamicState = &dynamic;
  info.layout = layout;
  info.renderPass = pass;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VT_VK(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  return pipeline;
}

Layouts createLayouts(VkDevice device) {
  Layouts out;
  const VkDescriptorSetLayoutBinding frameBindings[2] = {
      {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr}};  // shadow map
  VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  info.bindingCount = 2;
  info.pBindings = frameBindings;
  VT_VK(vkCreateDescriptorSetLayout(device, &info, nullptr, &out.frame));
  const VkDescriptorSetLayoutBinding materialBindings[2] = {
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr}};
  info.bindingCount = 2;
  info.pBindings = materialBindings;
  VT_VK(vkCreateDescriptorSetLayout(device, &info, nullptr, &out.material));
  const VkDescriptorSetLayout sets[2] = {out.frame, out.material};
  const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(ObjectConstants)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 2;
  layoutInfo.pSetLayouts = sets;
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &push;
  VT_VK(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &out.pipeline));
  return out;
}

void destroyLayouts(VkDevice device, Layouts& layouts) {
  vkDestroyPipelineLayout(device, layouts.pipeline, nullptr);
  vkDestroyDescriptorSetLayout(device, layouts.material, nullptr);
  vkDestroyDescriptorSetLayout(device, layouts.frame, nullptr);
  layouts = {};
}

PassPipelines createPassPipelines(const Device& dev, const Layouts& layouts, const PassKey& key) {
  VkDevice device = dev.device();
  PassPipelines out;
  out.key = key;
  out.renderPass = createRenderPass(dev, key);
  const std::array<VkShaderModule, 5> modules = {createShaderModule(device, kMeshVert), createShaderModule(device, kMeshFrag),
                                                 createShaderModule(device, kOverlayFrag), createShaderModule(device, kHandVert),
                                                 createShaderModule(device, kHandFrag)};
  // Modules are only needed while pipelines are created; free them even when creation throws.
  struct ModuleGuard {
    VkDevice device;
    const std::array<VkShaderModule, 5>& modules;
    ~ModuleGuard() {
      for (VkShaderModule m : modules) vkDestroyShaderModule(device, m, nullptr);
    }
  } guard{device, modules};
  out.textured = createPipeline(device, layouts.pipeline, out.renderPass, {modules[0], modules[1], false, false});
  out.texturedShadowed =
      createPipeline(device, layouts.pipeline, out.renderPass, {modules[0], modules[1], false, false, false, true});
  out.overlay = createPipeline(device, layouts.pipeline, out.renderPass, {modules[0], modules[2], false, true});
  out.hand = createPipeline(device, layouts.pipeline, out.renderPass, {modules[3], modules[4], true, false});
  out.rings = createRingPipeline(device, layouts.pipeline, out.renderPass);
  return out;
}

void destroyPassPipelines(VkDevice device, PassPipelines& pass) {
  for (VkPipeline p : {pass.textured, pass.texturedShadowed, pass.overlay, pass.hand, pass.rings}) {
    vkDestroyPipeline(device, p, nullptr);
  }
  vkDestroyRenderPass(device, pass.renderPass, nullptr);
  pass = {};
}

VkPipeline createHandShadowPipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass depthOnlyPass) {
  const VkShaderModule vert = createShaderModule(device, kHandVert);
  struct ModuleGuard {
    VkDevice device;
    VkShaderModule module;
    ~ModuleGuard() { vkDestroyShaderModule(device, module, nullptr); }
  } guard{device, vert};
  return createPipeline(device, layout, depthOnlyPass, {vert, VK_NULL_HANDLE, true, false, true});
}

}  // namespace vt::renderer
