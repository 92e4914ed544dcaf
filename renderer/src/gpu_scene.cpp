#include "gpu_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "vt/core/error.hpp"
#include "vt/renderer/vk_check.hpp"

namespace vt::renderer {
namespace {

VkDeviceSize align16(VkDeviceSize n) { return (n + 15) & ~VkDeviceSize(15); }

/// A CPU image on its way to the GPU: pixels already in the GPU format.
struct PendingImage {
  VkFormat format;
  int width, height;
  std::vector<std::uint8_t> bytes;
  VkDeviceSize stagingOffset = 0;
};

PendingImage fromTexture(const Image8& t) {
  return {VK_FORMAT_R8G8B8A8_SRGB, t.width, t.height, t.pixels};
}

PendingImage fromVibrationMap(const ImageF& map) {
  // 8 bits are plenty for a visual overlay and R8_UNORM is always linearly filterable.
  PendingImage out{VK_FORMAT_R8_UNORM, map.width, map.height, std::vector<std::uint8_t>(std::size_t(map.width) * map.height)};
  for (std::size_t i = 0; i < out.bytes.size(); ++i) {
    out.bytes[i] = std::uint8_t(std::clamp(map.pixels[i * std::size_t(map.channels)], 0.0f, 1.0f) * 255.0f + 0.5f);
  }
  return out;
}

bool canBlitMips(VkPhysicalDevice physical, VkFormat format) {
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(physical, format, &props);
  const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                    VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  return (props.optimalTilingFeatures & need) == need;
}

// Copies level 0 from the staging buffer, then halves down the mip chain with linear blits.
void recordImageUpload(VkCommandBuffer cmd, VkBuffer staging, const PendingImage& src, const GpuImage& dst) {
  const std::uint32_t levels = dst.spec.mipLevels;
  transitionImage(cmd, dst.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                  VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, levels, 1);
  VkBufferImageCopy copy{};
  copy.bufferOffset = src.stagingOffset;
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {std::uint32_t(src.width), std::uint32_t(src.height), 1};
  vkCmdCopyBufferToImage(cmd, staging, dst.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
  std::int32_t w = src.width, h = src.height;
  for (std::uint32_t level = 1; level < levels; ++level) {
    transitionImage(cmd, dst.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, level - 1, 1, 1);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, 1};
    blit.srcOffsets[1] = {w, h, 1};
    w = std::max(w / 2, 1);
    h = std::max(h / 2, 1);
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
    blit.dstOffsets[1] = {w, h, 1};
    vkCmdBlitImage(cmd, dst.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst.image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
    transitionImage(cmd, dst.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, level - 1, 1, 1);
  }
  transitionImage(cmd, dst.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, levels - 1, 1, 1);
}

}  // namespace

GpuScene::GpuScene(const Device& device, const Scene& scene, VkDescriptorSetLayout materialLayout,
                   VkSampler wrapSampler, VkSampler clampSampler)
    : m_device(device.device()) {
  scene.validate();

  // Geometry: scene meshes then the unit capsule for hand primitives, in one buffer pair.
  std::vector<const Mesh*> meshes;
  for (const Mesh& m : scene.meshes) meshes.push_back(&m);
  const Mesh capsule = makeCapsule(16, 6);
  meshes.push_back(&capsule);
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;
  std::vector<MeshRange> ranges;
  for (const Mesh* m : meshes) {
    if (m->indices.empty()) fail("scene: a mesh has no triangles");
    ranges.push_back({std::uint32_t(indices.size()), std::uint32_t(m->indices.size()), std::int32_t(vertices.size())});
    vertices.insert(vertices.end(), m->vertices.begin(), m->vertices.end());
    indices.insert(indices.end(), m->indices.begin(), m->indices.end());
  }
  m_handMesh = ranges.back();

  // Images: textures, vibration maps, then 1x1 defaults for materials without them.
  std::vector<PendingImage> pending;
  for (const Image8& t : scene.textures) pending.push_back(fromTexture(t));
  for (const ImageF& v : scene.vibrationMaps) {
    if (v.empty()) fail("scene: an empty vibration map");
    pending.push_back(fromVibrationMap(v));
  }
  const std::size_t whiteIndex = pending.size();
  pending.push_back({VK_FORMAT_R8G8B8A8_SRGB, 1, 1, {255, 255, 255, 255}});
  const std::size_t zeroIndex = pending.size();
  pending.push_back({VK_FORMAT_R8_UNORM, 1, 1, {0}});

  const VkDeviceSize vertexBytes = vertices.size() * sizeof(Vertex);
  const VkDeviceSize indexBytes = indices.size() * sizeof(std::uint32_t);
  VkDeviceSize stagingBytes = align16(vertexBytes) + align16(indexBytes);
  for (PendingImage& p : pending) {
    if (p.width <= 0 || p.height <= 0) fail("scene: an image has no pixels");
    p.stagingOffset = stagingBytes;
    stagingBytes += align16(p.bytes.size());
  }
  GpuBuffer staging(device, stagingBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                    VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  auto* bytes = static_cast<std::uint8_t*>(staging.mapped);
  std::memcpy(bytes, vertices.data(), vertexBytes);
  std::memcpy(bytes + align16(vertexBytes), indices.data(), indexBytes);
  for (const PendingImage& p : pending) std::memcpy(bytes + p.stagingOffset, p.bytes.data(), p.bytes.size());

  m_vertices = GpuBuffer(device, vertexBytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                         VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  m_indices = GpuBuffer(device, indexBytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  for (const PendingImage& p : pending) {
    const bool mips = canBlitMips(device.physicalDevice(), p.format);
    ImageSpec spec;
    spec.format = p.format;
    spec.extent = {std::uint32_t(p.width), std::uint32_t(p.height)};
    spec.mipLevels = mips ? std::uint32_t(std::floor(std::log2(std::max(p.width, p.height)))) + 1 : 1;
    spec.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    m_images.emplace_back(device, spec, false);
  }
  submitOnce(device, [&](VkCommandBuffer cmd) {
    const VkBufferCopy vertexCopy{0, 0, vertexBytes};
    vkCmdCopyBuffer(cmd, staging.buffer, m_vertices.buffer, 1, &vertexCopy);
    const VkBufferCopy indexCopy{align16(vertexBytes), 0, indexBytes};
    vkCmdCopyBuffer(cmd, staging.buffer, m_indices.buffer, 1, &indexCopy);
    for (std::size_t i = 0; i < pending.size(); ++i) recordImageUpload(cmd, staging.buffer, pending[i], m_images[i]);
  });

  // One descriptor set per material.
  const auto materialCount = std::uint32_t(std::max<std::size_t>(scene.materials.size(), 1));
  const VkDescriptorPoolSize poolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * materialCount};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = materialCount;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &poolSize;
  VT_VK(vkCreateDescriptorPool(m_device, &poolInfo, nullptr, &m_pool));
  std::vector<VkDescriptorSet> sets(scene.materials.size());
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = m_pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &materialLayout;
    VT_VK(vkAllocateDescriptorSets(m_device, &alloc, &sets[i]));
    const VkSampler sampler = m.wrapUv ? wrapSampler : clampSampler;
    const std::size_t albedo = m.albedoTexture >= 0 ? std::size_t(m.albedoTexture) : whiteIndex;
    const std::size_t vibration = m.vibrationMap >= 0 ? scene.textures.size() + std::size_t(m.vibrationMap) : zeroIndex;
    const VkDescriptorImageInfo images[2] = {
        {sampler, m_images[albedo].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        {sampler, m_images[vibration].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
    VkWriteDescriptorSet writes[2]{};
    for (std::uint32_t b = 0; b < 2; ++b) {
      writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      writes[b].dstSet = sets[i];
      writes[b].dstBinding = b;
      writes[b].descriptorCount = 1;
      writes[b].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
      writes[b].pImageInfo = &images[b];
    }
    vkUpdateDescriptorSets(m_device, 2, writes, 0, nullptr);
  }

  // Smallest objects first, the largest (table, floor) last: large surfaces are mostly behind the
  // small ones, so the depth test then skips their hidden fragments before shading (lavapipe
  // shades every fragment that passes on the CPU). Only the order of equal-depth fragments changes.
  std::vector<float> reach(scene.objects.size());
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    const Aabb box = bounds(scene.meshes[std::size_t(o.mesh)]);
    const glm::mat3 linear(o.T_world_object);
    reach[i] = glm::length(linear * (box.max - box.min));
  }
  std::vector<std::size_t> order(scene.objects.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return reach[a] < reach[b]; });
  for (const std::size_t i : order) {
    const SceneObject& o = scene.objects[i];
    const Material& m = scene.materials[std::size_t(o.material)];
    DrawItem item;
    item.mesh = ranges[std::size_t(o.mesh)];
    item.materialSet = sets[std::size_t(o.material)];
    item.constants.T_world_object = o.T_world_object;
    item.constants.baseColor = m.baseColor;
    // glm is column-major: row r of the uv transform is (M[0][r], M[1][r], M[2][r]).
    item.constants.uvRow0 = {m.uvTransform[0][0], m.uvTransform[1][0], m.uvTransform[2][0], 0.0f};
    item.constants.uvRow1 = {m.uvTransform[0][1], m.uvTransform[1][1], m.uvTransform[2][1], 0.0f};
    item.tactile = m.vibrationMap >= 0;
    m_draws.push_back(item);
  }
}

GpuScene::~GpuScene() {
  if (m_pool) vkDestroyDescriptorPool(m_device, m_pool, nullptr);
}

}  // namespace vt::renderer
