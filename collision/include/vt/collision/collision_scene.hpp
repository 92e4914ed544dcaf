#pragma once
// Two-level collision world: one MeshBvh per scene mesh (shared), one instance per scene
// object with its transform, and a top-level BVH over the instances' world boxes.
// Queries are const, lock-free and allocation-free: any number of threads may query one
// CollisionScene at once. A changed scene is a new CollisionScene, published as a new snapshot.
#include <memory>
#include <span>
#include <vector>

#include "vt/collision/bvh.hpp"
#include "vt/collision/mesh_bvh.hpp"
#include "vt/collision/query.hpp"
#include "vt/scene/scene.hpp"

namespace vt::collision {

/// The two-level collision world of one scene snapshot (see the file comment for threads).
class CollisionScene {
 public:
  /// An empty world (every query misses).
  CollisionScene() = default;
  /// Builds every mesh's BVH and the top level from scene.objects. Setup threads only.
  explicit CollisionScene(std::shared_ptr<const Scene> scene, const BuildConfig& config = {});

  /// Closest hit along the ray over all objects. Any thread.
  RayHit intersect(const Ray& ray) const noexcept;
  /// One intersect per ray; up to kMaxQueryBatch rays at a time share their BVH walks (their
  /// memory waits overlap: faster than one by one on large meshes). Any thread.
  void intersect(std::span<const Ray> rays, std::span<RayHit> out) const noexcept;
  /// Nearest surface point within the sphere (a fingertip), with depth and normal. Any thread.
  SphereContact sphereContact(const Sphere& sphere) const noexcept;
  /// One sphereContact per sphere (all contact points of the hands in one call; up to
  /// kMaxQueryBatch at a time share their BVH walks, which hides memory latency). Any thread.
  void sphereContacts(std::span<const Sphere> spheres, std::span<SphereContact> out) const noexcept;

  /// The scene the world was built from (meshes, materials, UVs). Any thread.
  const Scene& scene() const noexcept { return *m_scene; }
  const std::shared_ptr<const Scene>& scenePtr() const noexcept { return m_scene; }
  /// Instances (one per scene object) and their current transforms. Any thread.
  std::size_t objectCount() const noexcept { return m_instances.size(); }
  const glm::mat4& transform(std::uint32_t object) const noexcept { return m_instances[object].T_world_object; }

 private:
  struct Instance {
    std::shared_ptr<const MeshBvh> bvh;  // the mesh's, or a private one with the linear part baked in
    glm::mat4 T_world_object{1.0f};
    glm::mat4 T_world_bvh{1.0f};  // T_world_object without any baked linear part
    glm::mat4 T_bvh_world{1.0f};
    glm::mat3 normalToWorld{1.0f};  // inverse transpose of T_world_bvh's linear part
    float scale = 1.0f;             // uniform scale of T_world_bvh (distances bvh -> world)
    bool mirrored = false;          // the transform flips handedness (front faces swap)
    Aabb worldBox{};
  };

  bool topHasBoxes() const noexcept { return m_top.nodes.size() > 1; }
  void placeInstance(Instance& instance, std::uint32_t object, const glm::mat4& T_world_object);
  void buildTopLevel();
  struct Candidates;
  static PreparedRay localRay(const Instance& instance, const Ray& ray) noexcept;
  static RayHit hitFrom(const Instance& instance, std::uint32_t object, const MeshHit& best) noexcept;
  void rayBatch(std::span<const Ray> rays, std::span<RayHit> out) const noexcept;
  void sphereBatch(std::span<const Sphere> spheres, std::span<SphereContact> out) const noexcept;
  SphereContact contactFrom(const Sphere& sphere, const Instance& instance, std::uint32_t object, const MeshHit& best,
                            float bestD2) const noexcept;

  std::shared_ptr<const Scene> m_scene = std::make_shared<const Scene>();
  BuildConfig m_config;
  std::vector<std::shared_ptr<const MeshBvh>> m_meshBvhs;  // per scene mesh
  std::vector<Instance> m_instances;                        // per scene object
  std::vector<Aabb> m_instanceBoxes;
  Bvh m_top;
};

}  // namespace vt::collision
