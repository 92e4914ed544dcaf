#pragma once
// A vt::Scene uploaded to the GPU once: one vertex and one index buffer for every mesh (plus the
// unit capsule used for hand primitives), mipmapped textures and vibration maps, and one
// descriptor set per material (internal to the renderer).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gpu.hpp"
#include "vt/scene/scene.hpp"

namespace vt::renderer {

struct MeshRange {
  std::uint32_t firstIndex = 0;
  std::uint32_t indexCount = 0;
  std::int32_t vertexOffset = 0;
};

/// Push-constant block of the mesh shaders (mirrors `Object` in shaders/mesh.vert).
struct ObjectConstants {
  glm::mat4 T_world_object{1.0f};
  glm::vec4 baseColor{1.0f};
  glm::vec4 uvRow0{1, 0, 0, 0};
  glm::vec4 uvRow1{0, 1, 0, 0};
};
static_assert(sizeof(ObjectConstants) == 112, "fits the guaranteed 128-byte push-constant range");

struct DrawItem {
  MeshRange mesh;
  VkDescriptorSet materialSet = VK_NULL_HANDLE;
  ObjectConstants constants;
  bool tactile = false;  // has a vibration map (drawn again by the overlay pass)
};

class GpuScene {
 public:
  /// Uploads and waits. materialLayout: binding 0 albedo, binding 1 vibration map.
  GpuScene(const Device& device, const Scene& scene, VkDescriptorSetLayout materialLayout,
           VkSampler wrapSampler, VkSampler clampSampler);
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  const std::vector<DrawItem>& draws() const { return m_draws; }
  const MeshRange& handMesh() const { return m_handMesh; }
  VkBuffer vertexBuffer() const { return m_vertices.buffer; }
  VkBuffer indexBuffer() const { return m_indices.buffer; }

 private:
  VkDevice m_device;
  GpuBuffer m_vertices;
  GpuBuffer m_indices;
  std::vector<GpuImage> m_images;
  VkDescriptorPool m_pool = VK_NULL_HANDLE;
  std::vector<DrawItem> m_draws;
  MeshRange m_handMesh;
};

}  // namespace vt::renderer
