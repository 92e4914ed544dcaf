#include "vt/renderer/renderer.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstring>
#include <limits>

#include "contact_rings.hpp"
#include "gpu.hpp"
#include "gpu_scene.hpp"
#include "pipelines.hpp"
#include "shadow_pass.hpp"
#include "skinned_hands.hpp"
#include "vt/core/error.hpp"
#include "vt/renderer/vk_check.hpp"

namespace vt::renderer {
namespace {

/// Mirrors `Frame` in shaders/frame.glsl (std140).
struct FrameUniforms {
  glm::mat4 viewProj[2];
  glm::vec4 toLight;
  glm::vec4 lightColor;
  glm::vec4 overlay;
  ShadowUniforms shadow;
  glm::mat4 invViewProj[2];
  glm::vec4 viewport;
};

/// The uniform copy the shadow pass reads (copies 0 and 1 serve the views).
constexpr std::uint32_t kShadowCopy = 2;

/// Mirrors the per-instance attributes of shaders/hand.vert.
struct HandInstance {
  glm::vec4 aRadius;
  glm::vec4 b;
  glm::vec4 color;
};

constexpr float kDirectLight = 0.9f;
constexpr float kAmbientLight = 0.3f;
constexpr std::size_t kMaxCachedTargets = 4;

VkSampler createSampler(VkDevice device, VkSamplerAddressMode mode) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = VK_FILTER_LINEAR;
  info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  info.addressModeU = info.addressModeV = info.addressModeW = mode;
  info.maxLod = VK_LOD_CLAMP_NONE;
  VkSampler sampler = VK_NULL_HANDLE;
  VT_VK(vkCreateSampler(device, &info, nullptr, &sampler));
  return sampler;
}

}  // namespace

RenderTarget::RenderTarget() {
  static std::atomic<std::uint64_t> next{1};
  m_targetId = next.fetch_add(1);
}

/// Depth images and framebuffers for one target: one framebuffer per image, depth slot and pass
/// (one pass, or one per view when stereo is drawn per view through single-layer views). Depth
/// slots are the renderer's own depth images (one per frame slot) or the target's depth images.
struct TargetFramebuffers {
  std::uint64_t targetId = 0;
  std::uint64_t generation = 0;
  std::uint64_t lastUsed = 0;
  std::uint32_t passes = 1;
  std::uint32_t depthSlots = Renderer::kFramesInFlight;
  bool externalDepth = false;
  std::array<GpuImage, Renderer::kFramesInFlight> depth;  // unused with externalDepth
  std::vector<VkImageView> layerViews;      // per-view mode: single-layer views of target images
  std::vector<VkFramebuffer> framebuffers;  // [(image * depthSlots + depthSlot) * passes + pass]

  VkFramebuffer at(std::uint32_t image, std::uint32_t depthSlot, std::uint32_t pass) const {
    return framebuffers[(image * depthSlots + depthSlot) * passes + pass];
  }
};

struct Renderer::Impl {
  struct Slot {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    GpuBuffer uniforms;
    GpuBuffer instances;
    VkDescriptorSet frameSet = VK_NULL_HANDLE;
  };

  const Device& dev;
  VkDevice device;
  bool multiview;
  VkDeviceSize uniformStride;  // one FrameUniforms copy per view pass (dynamic offset)
  Layouts layouts;
  VkSampler wrapSampler = VK_NULL_HANDLE;
  VkSampler clampSampler = VK_NULL_HANDLE;
  VkCommandPool commandPool = VK_NULL_HANDLE;
  VkDescriptorPool framePool = VK_NULL_HANDLE;
  std::array<Slot, kFramesInFlight> slots;
  std::uint64_t frameCounter = 0;
  std::uint64_t resourceBuilds = 0;
  std::shared_ptr<const Scene> sceneData;
  std::unique_ptr<GpuScene> scene;
  std::vector<PassPipelines> passes;
  std::vector<std::unique_ptr<TargetFramebuffers>> targets;
  std::unique_ptr<ShadowPass> shadow;
  std::unique_ptr<ContactRings> rings;
  ShadowFrame shadowFrame;  // this frame's: when active, run the shadow pass and receive it
  std::vector<HandPrimitive> casterBounds;  // this frame's casters as primitives (reused storage)
  std::unique_ptr<SkinnedHands> skinnedHands;
  const RenderTarget* preparedTarget = nullptr;  // prepare(): its image, for the next render() into it
  AcquiredImage preparedImage;

  Impl(const Device& d, bool useMultiview)
      : dev(d), device(d.device()), multiview(useMultiview),
        uniformStride((sizeof(FrameUniforms) + d.uniformAlignment() - 1) / d.uniformAlignment() * d.uniformAlignment()) {}
  std::uint32_t passesFor(const RenderTarget& target) const { return multiview ? 1 : target.layers(); }
  ~Impl();
  void create();
  PassPipelines& passFor(const RenderTarget& target);
  TargetFramebuffers& framebuffersFor(const RenderTarget& target, const PassPipelines& pass);
  void destroyFramebuffers(TargetFramebuffers& t);
  void record(Slot& slot, RenderTarget& target, const AcquiredImage& image, const FrameDesc& frame,
              const PassHook& hook);
  /// The frame's hand (instances in the slot) with `pipeline`: the colour pass's or the shadow pass's.
  void drawHand(const Slot& slot, std::uint32_t handCount, VkPipeline pipeline) const;
};

void Renderer::Impl::create() {
  layouts = createLayouts(device);
  wrapSampler = createSampler(device, VK_SAMPLER_ADDRESS_MODE_REPEAT);
  clampSampler = createSampler(device, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = dev.queueFamily();
  VT_VK(vkCreateCommandPool(device, &poolInfo, nullptr, &commandPool));
  shadow = std::make_unique<ShadowPass>(dev, layouts.pipeline);
  rings = std::make_unique<ContactRings>(dev, kFramesInFlight);
  const VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, kFramesInFlight},
                                         {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kFramesInFlight}};
  VkDescriptorPoolCreateInfo descriptorInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  descriptorInfo.maxSets = kFramesInFlight;
  descriptorInfo.poolSizeCount = 2;
  descriptorInfo.pPoolSizes = sizes;
  VT_VK(vkCreateDescriptorPool(device, &descriptorInfo, nullptr, &framePool));
  for (Slot& slot : slots) {
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = commandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VT_VK(vkAllocateCommandBuffers(device, &alloc, &slot.cmd));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fenceInfo.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // the first wait returns at once
    VT_VK(vkCreateFence(device, &fenceInfo, nullptr, &slot.fence));
    const VkMemoryPropertyFlags hostMemory = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    slot.uniforms = GpuBuffer(dev, uniformStride * (kShadowCopy + 1), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, hostMemory);
    slot.instances = GpuBuffer(dev, sizeof(HandInstance) * kMaxHandPrimitives, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, hostMemory);
    VkDescriptorSetAllocateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    setInfo.descriptorPool = framePool;
    setInfo.descriptorSetCount = 1;
    setInfo.pSetLayouts = &layouts.frame;
    VT_VK(vkAllocateDescriptorSets(device, &setInfo, &slot.frameSet));
    const VkDescriptorBufferInfo bufferInfo{slot.uniforms.buffer, 0, sizeof(FrameUniforms)};
    const VkDescriptorImageInfo shadowMap = shadow->descriptor();
    VkWriteDescriptorSet writes[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
    writes[0].dstSet = writes[1].dstSet = slot.frameSet;
    writes[0].dstBinding = 0;
    writes[0].descriptorCount = 1;
    writes[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC;
    writes[0].pBufferInfo = &bufferInfo;
    writes[1].dstBinding = 1;
    writes[1].descriptorCount = 1;
    writes[1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    writes[1].pImageInfo = &shadowMap;
    vkUpdateDescriptorSets(device, 2, writes, 0, nullptr);
  }
  skinnedHands = std::make_unique<SkinnedHands>(dev, layouts.frame, kFramesInFlight, makeHandMesh());
}

Renderer::Impl::~Impl() {
  if (device) vkDeviceWaitIdle(device);
  for (auto& t : targets) destroyFramebuffers(*t);
  for (PassPipelines& p : passes) destroyPassPipelines(device, p);
  scene.reset();
  shadow.reset();
  rings.reset();
  skinnedHands.reset();
  for (Slot& slot : slots) {
    if (slot.fence) vkDestroyFence(device, slot.fence, nullptr);
    slot.uniforms.reset();
    slot.instances.reset();
  }
  if (framePool) vkDestroyDescriptorPool(device, framePool, nullptr);
  if (commandPool) vkDestroyCommandPool(device, commandPool, nullptr);
  if (wrapSampler) vkDestroySampler(device, wrapSampler, nullptr);
  if (clampSampler) vkDestroySampler(device, clampSampler, nullptr);
  if (layouts.pipeline) destroyLayouts(device, layouts);
}

PassPipelines& Renderer::Impl::passFor(const RenderTarget& target) {
  const bool externalDepth = target.depthImageCount() > 0;
  const PassKey key{target.colorFormat(), multiview ? target.layers() : 1, target.finalLayout(),
                    externalDepth ? target.depthFormat() : dev.depthFormat(), externalDepth};
  for (PassPipelines& p : passes) {
    if (p.key == key) return p;
  }
  passes.push_back(createPassPipelines(dev, layouts, key));
  ++resourceBuilds;
  return passes.back();
}

void Renderer::Impl::destroyFramebuffers(TargetFramebuffers& t) {
  for (VkFramebuffer f : t.framebuffers) vkDestroyFramebuffer(device, f, nullptr);
  for (VkImageView v : t.layerViews) vkDestroyImageView(device, v, nullptr);
  t.framebuffers.clear();
  t.layerViews.clear();
  for (GpuImage& d : t.depth) d.reset();
}

TargetFramebuffers& Renderer::Impl::framebuffersFor(const RenderTarget& target, const PassPipelines& pass) {
  for (auto& t : targets) {
    if (t->targetId == target.targetId() && t->generation == target.generation()) {
      t->lastUsed = frameCounter;
      return *t;
    }
  }
  // A new target, or a recreated one (resize): retire stale entries once the GPU is done with them.
  const bool recreated = std::any_of(targets.begin(), targets.end(), [&](auto& t) { return t->targetId == target.targetId(); });
  if (recreated || targets.size() >= kMaxCachedTargets) {
    VT_VK(vkDeviceWaitIdle(device));
    auto stale = std::find_if(targets.begin(), targets.end(), [&](auto& t) { return t->targetId == target.targetId(); });
    if (stale == targets.end()) {
      stale = std::min_element(targets.begin(), targets.end(), [](auto& a, auto& b) { return a->lastUsed < b->lastUsed; });
    }
    destroyFramebuffers(**stale);
    targets.erase(stale);
  }
  ++resourceBuilds;
  auto entry = std::make_unique<TargetFramebuffers>();
  entry->targetId = target.targetId();
  entry->generation = target.generation();
  entry->lastUsed = frameCounter;
  entry->passes = passesFor(target);
  entry->externalDepth = target.depthImageCount() > 0;
  if (entry->externalDepth) entry->depthSlots = target.depthImageCount();
  const VkExtent2D extent = target.extent();
  for (GpuImage& depth : entry->depth) {
    if (entry->externalDepth) break;  // the target brings its own
    ImageSpec spec;
    spec.format = dev.depthFormat();
    spec.extent = extent;
    spec.layers = pass.key.views;  // per-view passes run one after another and share one layer
    spec.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    spec.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    depth = GpuImage(dev, spec, true);
  }
  // Per-view passes draw into one layer of the target's depth images (own depth shares one layer).
  const VkImageAspectFlags depthAspect = depthAspectOf(pass.key.depthFormat);
  for (std::uint32_t i = 0; i < target.imageCount(); ++i) {
    for (std::uint32_t s = 0; s < entry->depthSlots; ++s) {
      for (std::uint32_t p = 0; p < entry->passes; ++p) {
        VkImageView color = target.imageView(i);
        VkImageView depth = entry->externalDepth ? target.depthImageView(s) : entry->depth[s].view;
        if (entry->passes > 1) {
          color = createView(device, target.image(i), target.colorFormat(), VK_IMAGE_ASPECT_COLOR_BIT, 1, 1, false, p);
          entry->layerViews.push_back(color);
          if (entry->externalDepth) {
            depth = createView(device, target.depthImage(s), pass.key.depthFormat, depthAspect, 1, 1, false, p);
            entry->layerViews.push_back(depth);
          }
        }
        const VkImageView views[2] = {color, depth};
        VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        info.renderPass = pass.renderPass;
        info.attachmentCount = 2;
        info.pAttachments = views;
        info.width = extent.width;
        info.height = extent.height;
        info.layers = 1;  // multiview takes its layers from the view mask
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        VT_VK(vkCreateFramebuffer(device, &info, nullptr, &framebuffer));
        entry->framebuffers.push_back(framebuffer);
      }
    }
  }
  targets.push_back(std::move(entry));
  return *targets.back();
}

void Renderer::Impl::record(Slot& slot, RenderTarget& target, const AcquiredImage& image, const FrameDesc& frame,
                            const PassHook& hook) {
  PassPipelines& pass = passFor(target);
  TargetFramebuffers& fb = framebuffersFor(target, pass);
  const auto slotIndex = std::uint32_t(frameCounter % kFramesInFlight);
  if (fb.externalDepth && image.depthIndex >= fb.depthSlots) {
    fail("renderer: depth image ", image.depthIndex, " of ", fb.depthSlots);
  }
  const std::uint32_t depthSlot = fb.externalDepth ? image.depthIndex : slotIndex;
  const VkExtent2D extent = target.extent();

  VT_VK(vkResetCommandBuffer(slot.cmd, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VT_VK(vkBeginCommandBuffer(slot.cmd, &begin));
  if (scene && shadowFrame.active()) {
    shadow->begin(slot.cmd);
    const auto shadowOffset = std::uint32_t(kShadowCopy * uniformStride);
    vkCmdBindDescriptorSets(slot.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layouts.pipeline, 0, 1, &slot.frameSet, 1,
                            &shadowOffset);
    if (!frame.hand.empty()) drawHand(slot, std::uint32_t(frame.hand.size()), shadow->casterPipeline());
    skinnedHands->record(slot.cmd, slotIndex, shadow->renderPass(), slot.frameSet, shadowOffset, frame.hands, true);
    shadow->end(slot.cmd);
  }
  VkClearValue clears[2];
  clears[0].color = {{frame.clearColor.r, frame.clearColor.g, frame.clearColor.b, frame.clearColor.a}};
  clears[1].depthStencil = {1.0f, 0};
  const VkViewport viewport{0.0f, 0.0f, float(extent.width), float(extent.height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent};
  const VkDeviceSize zero = 0;
  for (std::uint32_t p = 0; p < fb.passes; ++p) {
    VkRenderPassBeginInfo passBegin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    passBegin.renderPass = pass.renderPass;
    passBegin.framebuffer = fb.at(image.index, depthSlot, p);
    passBegin.renderArea = {{0, 0}, extent};
    passBegin.clearValueCount = 2;
    passBegin.pClearValues = clears;
    vkCmdBeginRenderPass(slot.cmd, &passBegin, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdSetViewport(slot.cmd, 0, 1, &viewport);
    vkCmdSetScissor(slot.cmd, 0, 1, &scissor);
    // Pass p reads the uniforms copy whose viewProj[0] is view p (multiview: copy 0 holds both).
    const auto uniformOffset = std::uint32_t(p * uniformStride);
    vkCmdBindDescriptorSets(slot.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layouts.pipeline, 0, 1, &slot.frameSet, 1,
                            &uniformOffset);
    if (scene) {
      const VkBuffer vertices = scene->vertexBuffer();
      vkCmdBindVertexBuffers(slot.cmd, 0, 1, &vertices, &zero);
      vkCmdBindIndexBuffer(slot.cmd, scene->indexBuffer(), 0, VK_INDEX_TYPE_UINT32);
      auto drawAll = [&](VkPipeline pipeline, bool tactileOnly) {
        vkCmdBindPipeline(slot.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        VkDescriptorSet bound = VK_NULL_HANDLE;  // objects sharing a material bind it once
        for (const DrawItem& d : scene->draws()) {
          if (tactileOnly && !d.tactile) continue;
          if (d.materialSet != bound) {
            vkCmdBindDescriptorSets(slot.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layouts.pipeline, 1, 1, &d.materialSet, 0,
                                    nullptr);
            bound = d.materialSet;
          }
          vkCmdPushConstants(slot.cmd, layouts.pipeline, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                             sizeof(ObjectConstants), &d.constants);
          vkCmdDrawIndexed(slot.cmd, d.mesh.indexCount, 1, d.mesh.firstIndex, d.mesh.vertexOffset, 0);
        }
      };
      // Where the hand's shadow can fall, the receiving pipeline draws first; the plain one then
      // fails the depth test there (same depth, LESS), so no pixel is shaded twice.
      if (shadowFrame.active()) {
        glm::mat4 viewProjs[2];
        const std::uint32_t viewCount = fb.passes > 1 ? 1 : std::uint32_t(frame.views.size());
        for (std::uint32_t v = 0; v < viewCount; ++v) {
          const CameraView& view = frame.views[fb.passes > 1 ? p : v];
          viewProjs[v] = view.projection() * view.view();
        }
        const VkRect2D reach = shadowScissor(shadowFrame, {viewProjs, viewCount}, extent);
        if (reach.extent.width > 0 && reach.extent.height > 0) {
          vkCmdSetScissor(slot.cmd, 0, 1, &reach);
          drawAll(pass.texturedShadowed, false);
          vkCmdSetScissor(slot.cmd, 0, 1, &scissor);
        }
      }
      drawAll(pass.textured, false);
      if (frame.overlay && frame.overlayOpacity > 0.0f) drawAll(pass.overlay, true);
      if (!frame.hand.empty()) drawHand(slot, std::uint32_t(frame.hand.size()), pass.hand);
      rings->draw(slot.cmd, slotIndex, pass.rings);
    }
    skinnedHands->record(slot.cmd, slotIndex, pass.renderPass, slot.frameSet, uniformOffset, frame.hands);
    if (hook) hook(slot.cmd);
    vkCmdEndRenderPass(slot.cmd);
  }
  target.recordAfterPass(slot.cmd, image.index);
  VT_VK(vkEndCommandBuffer(slot.cmd));
}

void Renderer::Impl::drawHand(const Slot& slot, std::uint32_t handCount, VkPipeline pipeline) const {
  const VkDeviceSize zero = 0;
  const VkBuffer vertices = scene->vertexBuffer();
  vkCmdBindPipeline(slot.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  vkCmdBindVertexBuffers(slot.cmd, 0, 1, &vertices, &zero);
  vkCmdBindVertexBuffers(slot.cmd, 1, 1, &slot.instances.buffer, &zero);
  vkCmdBindIndexBuffer(slot.cmd, scene->indexBuffer(), 0, VK_INDEX_TYPE_UINT32);
  const MeshRange& capsule = scene->handMesh();
  vkCmdDrawIndexed(slot.cmd, capsule.indexCount, handCount, capsule.firstIndex, capsule.vertexOffset, 0);
}

Renderer::Renderer(std::shared_ptr<Device> device, const RendererOptions& options) : m_device(std::move(device)) {
  if (!m_device) fail("renderer: no device");
  const bool multiview = options.stereo == StereoMode::Multiview ||
                         (options.stereo == StereoMode::Auto && m_device->multiviewReliable());
  m_impl = std::make_unique<Impl>(*m_device, multiview);
  m_impl->create();
}

Renderer::~Renderer() = default;

void Renderer::setScene(std::shared_ptr<const Scene> scene) {
  waitIdle();  // frames in flight may still read the old scene's buffers
  m_impl->scene.reset();
  m_impl->sceneData = std::move(scene);
  if (m_impl->sceneData) {
    m_impl->scene = std::make_unique<GpuScene>(*m_device, *m_impl->sceneData, m_impl->layouts.material,
                                               m_impl->wrapSampler, m_impl->clampSampler);
  }
  m_impl->shadow->setScene(m_impl->sceneData.get());
}

bool Renderer::prepare(RenderTarget& target) {
  Impl& im = *m_impl;
  if (im.preparedTarget == &target) return true;
  if (im.preparedTarget) fail("renderer: a frame for another target is prepared; render() it first");
  const auto slotIndex = std::uint32_t(im.frameCounter % kFramesInFlight);
  VT_VK(vkWaitForFences(im.device, 1, &im.slots[slotIndex].fence, VK_TRUE, std::numeric_limits<std::uint64_t>::max()));
  if (!target.acquire(slotIndex, im.preparedImage)) return false;
  im.preparedTarget = &target;
  return true;
}

bool Renderer::render(RenderTarget& target, const FrameDesc& frame) {
  if (frame.views.empty() || frame.views.size() > 2 || frame.views.size() != target.layers()) {
    fail("renderer: frame has ", frame.views.size(), " views but the target has ", target.layers(), " layers");
  }
  if (frame.hand.size() > kMaxHandPrimitives) {
    fail("renderer: ", frame.hand.size(), " hand primitives exceed the limit of ", kMaxHandPrimitives);
  }
  if (frame.contacts.size() > kMaxContactMarkers) {
    fail("renderer: ", frame.contacts.size(), " contact markers exceed the limit of ", kMaxContactMarkers);
  }
  if (frame.hands.size() > kMaxSkinnedHands) {
    fail("renderer: ", frame.hands.size(), " skinned hands exceed the limit of ", kMaxSkinnedHands);
  }
  Impl& im = *m_impl;
  const auto slotIndex = std::uint32_t(im.frameCounter % kFramesInFlight);
  Impl::Slot& slot = im.slots[slotIndex];
  if (!prepare(target)) return false;  // waits and acquires, unless done ahead
  const AcquiredImage image = im.preparedImage;
  im.preparedTarget = nullptr;

  // Copy k serves the pass of view k: its viewProj[0] is view k, and copy 0 also carries view 1 in
  // viewProj[1] for multiview (gl_ViewIndex picks the matrix).
  const glm::vec3 lightDir = im.sceneData ? im.sceneData->lightDirection : glm::vec3(-0.4f, -1.0f, -0.3f);
  // The skinned hands cast too: their joint capsules bound where their shadow can fall.
  im.casterBounds = frame.hand;
  for (const SkinnedHand& h : frame.hands) appendHandPrimitives(h.pose, h.color, im.casterBounds);
  im.shadowFrame = im.shadow->frame(im.casterBounds);
  const ShadowUniforms& shadow = im.shadowFrame.uniforms;
  for (std::size_t copy = 0; copy <= kShadowCopy; ++copy) {
    FrameUniforms uniforms{};
    for (std::size_t v = 0; v < 2; ++v) {
      const CameraView& view = frame.views[std::min(copy + v, frame.views.size() - 1)];  // clamped for the shadow copy
      uniforms.viewProj[v] = view.projection() * view.view();
    }
    uniforms.toLight = glm::vec4(-glm::normalize(lightDir), 0.0f);
    uniforms.lightColor = {kDirectLight, kDirectLight, kDirectLight, kAmbientLight};
    uniforms.overlay = {std::clamp(frame.overlayOpacity, 0.0f, 1.0f), 0.0f, 0.0f, 0.0f};
    uniforms.shadow = shadow;
    for (std::size_t v = 0; v < 2; ++v) uniforms.invViewProj[v] = glm::inverse(uniforms.viewProj[v]);
    uniforms.viewport = {1.0f / float(target.extent().width), 1.0f / float(target.extent().height), 0.0f, 0.0f};
    if (copy == kShadowCopy) uniforms.viewProj[0] = uniforms.viewProj[1] = shadow.lightViewProj;
    std::memcpy(static_cast<std::uint8_t*>(slot.uniforms.mapped) + copy * im.uniformStride, &uniforms, sizeof(uniforms));
  }
  auto* instances = static_cast<HandInstance*>(slot.instances.mapped);
  for (std::size_t i = 0; i < frame.hand.size(); ++i) {
    const HandPrimitive& p = frame.hand[i];
    instances[i] = {glm::vec4(p.a_world, p.radius_m), glm::vec4(p.b_world, 0.0f), p.color};
  }
  im.rings->upload(slotIndex, frame.contacts);
  im.skinnedHands->update(slotIndex, frame.hands);

  static const PassHook kNoHook;
  im.record(slot, target, image, frame, frame.ui ? m_passHook : kNoHook);
  VT_VK(vkResetFences(im.device, 1, &slot.fence));
  const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = image.waitSemaphore ? 1 : 0;
  submit.pWaitSemaphores = &image.waitSemaphore;
  submit.pWaitDstStageMask = &waitStage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &slot.cmd;
  submit.signalSemaphoreCount = image.signalSemaphore ? 1 : 0;
  submit.pSignalSemaphores = &image.signalSemaphore;
  VT_VK(vkQueueSubmit(m_device->queue(), 1, &submit, slot.fence));
  target.submitted(image, slot.fence);
  ++im.frameCounter;
  return true;
}

bool Renderer::usesMultiview() const { return m_impl->multiview; }

std::uint64_t Renderer::resourceBuilds() const { return m_impl->resourceBuilds + m_impl->skinnedHands->builds(); }

void Renderer::setHandModel(const HandMesh& right) {
  waitIdle();  // frames in flight may still read the old mesh
  m_impl->skinnedHands->setModel(right);
}

VkRenderPass Renderer::renderPassFor(const RenderTarget& target) { return m_impl->passFor(target).renderPass; }

void Renderer::waitIdle() {
  for (Impl::Slot& slot : m_impl->slots) {
    VT_VK(vkWaitForFences(m_impl->device, 1, &slot.fence, VK_TRUE, std::numeric_limits<std::uint64_t>::max()));
  }
}

}  // namespace vt::renderer
