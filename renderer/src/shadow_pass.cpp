#include "shadow_pass.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pipelines.hpp"
#include "vt/core/error.hpp"
#include "vt/renderer/vk_check.hpp"

namespace vt::renderer {
namespace {

constexpr float kBias_m = 0.0005f;       // light-space depth bias (the hand is the only caster)
constexpr float kTapSpacing_texels = 1.5f;
constexpr float kCasterMargin_m = 0.01f;  // depth room around the casters and the scene

/// A depth format that can be both drawn into and sampled, preferring 16 bits (enough for an
/// orthographic range of a metre or two); whether it filters linearly (hardware 2x2 PCF).
VkFormat pickMapFormat(VkPhysicalDevice physical, bool& linear) {
  for (VkFormat format : {VK_FORMAT_D16_UNORM, VK_FORMAT_D32_SFLOAT}) {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(physical, format, &props);
    const VkFormatFeatureFlags need =
        VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
    if ((props.optimalTilingFeatures & need) == need) {
      linear = (props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
      return format;
    }
  }
  fail("renderer: the device has no depth format that can be sampled for shadows");
}

VkRenderPass createDepthOnlyPass(VkDevice device, VkFormat format, VkImageLayout finalLayout) {
  const VkAttachmentDescription attachment{0, format, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR,
                                           VK_ATTACHMENT_STORE_OP_STORE, VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                           VK_ATTACHMENT_STORE_OP_DONT_CARE, VK_IMAGE_LAYOUT_UNDEFINED, finalLayout};
  const VkAttachmentReference depth{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.pDepthStencilAttachment = &depth;
  const VkPipelineStageFlags tests = VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  const VkAccessFlags depthAccess = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  // In: the previous frame's fragment shaders finished reading the map (write after read).
  // Out: this frame's textured pass reads what was written.
  const VkSubpassDependency dependencies[2] = {
      {VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, tests, 0, depthAccess, 0},
      {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
       VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, 0}};
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 1;
  info.pAttachments = &attachment;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = dependencies;
  VkRenderPass pass = VK_NULL_HANDLE;
  VT_VK(vkCreateRenderPass(device, &info, nullptr, &pass));
  return pass;
}

}  // namespace

ShadowPass::ShadowPass(const Device& dev, VkPipelineLayout layout) : m_device(dev.device()) {
  bool linear = false;
  ImageSpec spec;
  spec.format = pickMapFormat(dev.physicalDevice(), linear);
  spec.extent = {kMapSize, kMapSize};
  spec.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  spec.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  m_map = GpuImage(dev, spec, false);
  // The textured pass may sample the map before any pass drew into it (strength 0 then).
  submitOnce(dev, [&](VkCommandBuffer cmd) {
    transitionImage(cmd, m_map.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED, kReadLayout, 0, 1, 1);
  });
  VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sampler.magFilter = sampler.minFilter = linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  sampler.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  sampler.addressModeU = sampler.addressModeV = sampler.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
  sampler.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;  // outside the map: lit
  sampler.compareEnable = VK_TRUE;
  sampler.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;  // 1 (lit) where the reference is not behind a caster
  VT_VK(vkCreateSampler(m_device, &sampler, nullptr, &m_sampler));
  m_renderPass = createDepthOnlyPass(m_device, spec.format, kReadLayout);
  VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fb.renderPass = m_renderPass;
  fb.attachmentCount = 1;
  fb.pAttachments = &m_map.view;
  fb.width = fb.height = kMapSize;
  fb.layers = 1;
  VT_VK(vkCreateFramebuffer(m_device, &fb, nullptr, &m_framebuffer));
  m_pipeline = createHandShadowPipeline(m_device, layout, m_renderPass);
}

ShadowPass::~ShadowPass() {
  vkDestroyPipeline(m_device, m_pipeline, nullptr);
  vkDestroyFramebuffer(m_device, m_framebuffer, nullptr);
  vkDestroyRenderPass(m_device, m_renderPass, nullptr);
  vkDestroySampler(m_device, m_sampler, nullptr);
}

void ShadowPass::setScene(const Scene* scene) {
  m_haveScene = false;
  if (!scene || scene->objects.empty()) return;
  m_forward = glm::normalize(scene->lightDirection);
  // As a camera looking along the light (right, up, -forward right-handed; clip y flipped like
  // CameraView::projection), so the hand's triangles keep their winding and back-face culling.
  const glm::vec3 helper = std::abs(m_forward.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(0.0f, 0.0f, -1.0f);
  m_right = glm::normalize(glm::cross(m_forward, helper));
  m_up = glm::cross(m_right, m_forward);
  m_min = glm::vec3(std::numeric_limits<float>::max());
  m_max = -m_min;
  m_objectBounds.clear();
  m_sceneBounds = {m_min, m_max};
  for (const SceneObject& object : scene->objects) {
    const Aabb box = bounds(scene->meshes[std::size_t(object.mesh)]);
    Aabb worldBox{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(-std::numeric_limits<float>::max())};
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 local{corner & 1 ? box.max.x : box.min.x, corner & 2 ? box.max.y : box.min.y,
                            corner & 4 ? box.max.z : box.min.z};
      const glm::vec3 world = glm::vec3(object.T_world_object * glm::vec4(local, 1.0f));
      const glm::vec3 light{glm::dot(world, m_right), glm::dot(world, m_up), glm::dot(world, m_forward)};
      m_min = glm::min(m_min, light);
      m_max = glm::max(m_max, light);
      worldBox = {glm::min(worldBox.min, world), glm::max(worldBox.max, world)};
    }
    m_objectBounds.push_back(worldBox);
    m_sceneBounds = {glm::min(m_sceneBounds.min, worldBox.min), glm::max(m_sceneBounds.max, worldBox.max)};
  }
  m_haveScene = m_max.x > m_min.x && m_max.y > m_min.y;
}

ShadowFrame ShadowPass::frame(const std::vector<HandPrimitive>& casters) const {
  ShadowFrame result;
  ShadowUniforms& out = result.uniforms;
  if (!m_haveScene || casters.empty()) return result;
  // The casters' extent along the light: the map's depth range starts in front of the nearest one.
  float nearest = m_min.z;
  for (const HandPrimitive& p : casters) {
    nearest = std::min({nearest, glm::dot(p.a_world, m_forward) - p.radius_m, glm::dot(p.b_world, m_forward) - p.radius_m});
  }
  const float zNear = nearest - kCasterMargin_m, zFar = m_max.z + kCasterMargin_m;
  const glm::vec2 mid = 0.5f * (glm::vec2(m_min) + glm::vec2(m_max));
  const glm::vec2 half = 0.5f * (glm::vec2(m_max) - glm::vec2(m_min));
  const float depth = zFar - zNear;
  glm::mat4& m = out.lightViewProj;  // column-major: m[column][row]
  m = glm::mat4(0.0f);
  for (int i = 0; i < 3; ++i) {
    m[i][0] = m_right[i] / half.x;
    m[i][1] = -m_up[i] / half.y;
    m[i][2] = m_forward[i] / depth;
  }
  m[3] = {-mid.x / half.x, mid.y / half.y, -zNear / depth, 1.0f};
  // The map uv rectangle the casters' shadow (widened by the filter's reach) can fall in.
  const float spacing = kTapSpacing_texels / float(kMapSize);
  const float reach = spacing + 1.0f / float(kMapSize);
  glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const HandPrimitive& p : casters) {
    const glm::vec2 r = glm::vec2(p.radius_m) / (2.0f * half) + reach;
    for (const glm::vec3& point : {p.a_world, p.b_world}) {
      const glm::vec2 uv = glm::vec2(m * glm::vec4(point, 1.0f)) * 0.5f + 0.5f;
      lo = glm::min(lo, uv - r);
      hi = glm::max(hi, uv + r);
    }
  }
  lo = glm::max(lo, glm::vec2(0.0f));
  hi = glm::min(hi, glm::vec2(1.0f));
  if (lo.x >= hi.x || lo.y >= hi.y) return {};  // the shadow misses the scene
  out.shadow = {kStrength, spacing, kBias_m / depth, 0.0f};
  out.rect = {lo, hi};
  // Where the shadow can fall: the lines along the light through the rectangle's corners, taken
  // at each receiver's lowest and highest height (or across the scene's depth when the light is
  // horizontal), bounded by the scene.
  Aabb box{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(-std::numeric_limits<float>::max())};
  for (int corner = 0; corner < 4; ++corner) {
    const glm::vec2 ndc = glm::vec2(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y) * 2.0f - 1.0f;
    const glm::vec3 base = m_right * (mid.x + ndc.x * half.x) + m_up * (mid.y - ndc.y * half.y);
    auto add = [&](float t) {
      const glm::vec3 p = base + m_forward * t;
      box = {glm::min(box.min, p), glm::max(box.max, p)};
    };
    if (std::abs(m_forward.y) < 1e-3f) {
      add(m_min.z);
      add(m_max.z);
      continue;
    }
    for (const Aabb& receiver : m_objectBounds) {
      for (float height : {receiver.min.y, receiver.max.y}) add((height - base.y) / m_forward.y);
    }
  }
  box = {glm::max(box.min, m_sceneBounds.min), glm::min(box.max, m_sceneBounds.max)};
  if (glm::any(glm::greaterThan(box.min, box.max))) return {};  // it misses every receiver
  for (int corner = 0; corner < 8; ++corner) {
    result.reach[std::size_t(corner)] = {corner & 1 ? box.max.x : box.min.x, corner & 2 ? box.max.y : box.min.y,
                                         corner & 4 ? box.max.z : box.min.z};
  }
  return result;
}

VkRect2D shadowScissor(const ShadowFrame& frame, std::span<const glm::mat4> viewProjs, VkExtent2D extent) {
  const VkRect2D whole{{0, 0}, extent};
  glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::mat4& viewProj : viewProjs) {
    for (const glm::vec3& corner : frame.reach) {
      const glm::vec4 clip = viewProj * glm::vec4(corner, 1.0f);
      if (clip.w <= 1e-4f) return whole;  // behind or at the camera: its projection is unbounded
      const glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(extent.width, extent.height);
      lo = glm::min(lo, pixel);
      hi = glm::max(hi, pixel);
    }
  }
  lo = glm::clamp(glm::floor(lo) - 1.0f, glm::vec2(0.0f), glm::vec2(extent.width, extent.height));
  hi = glm::clamp(glm::ceil(hi) + 1.0f, glm::vec2(0.0f), glm::vec2(extent.width, extent.height));
  if (hi.x <= lo.x || hi.y <= lo.y) return {{0, 0}, {0, 0}};
  return {{std::int32_t(lo.x), std::int32_t(lo.y)}, {std::uint32_t(hi.x - lo.x), std::uint32_t(hi.y - lo.y)}};
}

void ShadowPass::begin(VkCommandBuffer cmd) const {
  VkClearValue clear;
  clear.depthStencil = {1.0f, 0};
  VkRenderPassBeginInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  info.renderPass = m_renderPass;
  info.framebuffer = m_framebuffer;
  info.renderArea = {{0, 0}, {kMapSize, kMapSize}};
  info.clearValueCount = 1;
  info.pClearValues = &clear;
  vkCmdBeginRenderPass(cmd, &info, VK_SUBPASS_CONTENTS_INLINE);
  const VkViewport viewport{0.0f, 0.0f, float(kMapSize), float(kMapSize), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {kMapSize, kMapSize}};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace vt::renderer
