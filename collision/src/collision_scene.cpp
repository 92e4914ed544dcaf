#include "vt/collision/collision_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "vt/core/error.hpp"

namespace vt::collision {
namespace {

// Depth-first walk of the (small) top level. `distance(node)` returns a key that is < limit()
// when the node may hold something better; `leaf(primId)` tests one instance.
template <class Distance, class Limit, class Leaf>
void walkTop(const Bvh& top, Distance&& distance, Limit&& limit, Leaf&& leaf) noexcept {
  if (top.empty()) return;
  // A root that is a leaf is a scene of one object (the top level's leaves hold one each): its
  // own BVH's root test culls as well, and there is nothing to walk.
  const BvhNode& root = top.nodes[0];
  if (root.isLeaf()) {
    if (!(0.0f < limit())) return;
    for (std::uint32_t i = 0; i < root.count; ++i) leaf(top.primIds[root.index + i]);
    return;
  }
  if (!(distance(root) < limit())) return;
  struct Entry {
    std::uint32_t node;
    float key;
  };
  Entry stack[kTraversalStackSize];
  int size = 0;
  stack[size++] = {0, 0.0f};
  while (size > 0) {
    const Entry e = stack[--size];
    if (!(e.key < limit())) continue;
    const BvhNode& node = top.nodes[e.node];
    if (node.isLeaf()) {
      for (std::uint32_t i = 0; i < node.count; ++i) leaf(top.primIds[node.index + i]);
      continue;
    }
    const float a = distance(top.nodes[node.index]), b = distance(top.nodes[node.index + 1]);
    // Push the farther child first so the nearer one is visited next.
    const bool aFirst = a <= b;
    const Entry near{aFirst ? node.index : node.index + 1, aFirst ? a : b};
    const Entry far{aFirst ? node.index + 1 : node.index, aFirst ? b : a};
    // The builder limits depth (bvh.cpp), so the stack never fills: checked builds fail, release counts.
    if (far.key < limit() && VT_INVARIANT(size < kTraversalStackSize)) stack[size++] = far;
    if (near.key < limit() && VT_INVARIANT(size < kTraversalStackSize)) stack[size++] = near;
  }
}

bool isSimilarity(const glm::mat3& a, float& scale) noexcept {
  const float l0 = glm::dot(a[0], a[0]), l1 = glm::dot(a[1], a[1]), l2 = glm::dot(a[2], a[2]);
  const float s2 = (l0 + l1 + l2) / 3.0f;
  scale = std::sqrt(s2);
  const float tol = 1e-4f * s2;
  return s2 > 0.0f && std::abs(l0 - s2) < tol && std::abs(l1 - s2) < tol && std::abs(l2 - s2) < tol &&
         std::abs(glm::dot(a[0], a[1])) < tol && std::abs(glm::dot(a[1], a[2])) < tol &&
         std::abs(glm::dot(a[0], a[2])) < tol;
}

Aabb transformBox(const Aabb& b, const glm::mat4& m) noexcept {
  // Arvo's method: the box of a transformed box from the matrix entries.
  Aabb out{glm::vec3(m[3]), glm::vec3(m[3])};
  for (int col = 0; col < 3; ++col) {
    const glm::vec3 e0 = glm::vec3(m[col]) * b.min[col], e1 = glm::vec3(m[col]) * b.max[col];
    out.min += glm::min(e0, e1);
    out.max += glm::max(e0, e1);
  }
  return out;
}

}  // namespace

CollisionScene::CollisionScene(std::shared_ptr<const Scene> scene, const BuildConfig& config)
    : m_scene(std::move(scene)), m_config(config) {
  if (!m_scene) fail("collision: no scene given");
  m_scene->validate();
  m_meshBvhs.reserve(m_scene->meshes.size());
  for (std::size_t i = 0; i < m_scene->meshes.size(); ++i) {
    m_meshBvhs.push_back(std::make_shared<const MeshBvh>(m_scene->meshes[i], str("#", i), config));
  }
  m_instances.resize(m_scene->objects.size());
  m_instanceBoxes.resize(m_instances.size());
  for (std::uint32_t i = 0; i < m_instances.size(); ++i) {
    placeInstance(m_instances[i], i, m_scene->objects[i].T_world_object);
  }
  buildTopLevel();
}

void CollisionScene::placeInstance(Instance& instance, std::uint32_t object, const glm::mat4& T_world_object) {
  const SceneObject& source = m_scene->objects[object];
  const glm::mat3 linear(T_world_object);
  if (!(std::abs(glm::determinant(linear)) > 0.0f)) {
    fail("collision: object '", source.name, "': transform is not invertible");
  }
  instance.T_world_object = T_world_object;
  float scale = 1.0f;
  if (isSimilarity(linear, scale)) {
    instance.bvh = m_meshBvhs[std::size_t(source.mesh)];
    instance.T_world_bvh = T_world_object;
    instance.scale = scale;
    instance.mirrored = false;  // tests run in the object frame, where winding is unchanged
    instance.normalToWorld = glm::transpose(glm::inverse(linear));
  } else {
    // Distances do not survive non-uniform scale or shear: bake the linear part into a
    // private BVH so closest-point queries stay exact.
    instance.bvh = std::make_shared<const MeshBvh>(m_scene->meshes[std::size_t(source.mesh)], source.name,
                                                   m_config, linear);
    instance.T_world_bvh = glm::translate(glm::mat4(1.0f), glm::vec3(T_world_object[3]));
    instance.scale = 1.0f;
    instance.mirrored = glm::determinant(linear) < 0.0f;
    instance.normalToWorld = glm::mat3(1.0f);
  }
  instance.T_bvh_world = glm::inverse(instance.T_world_bvh);
  instance.worldBox = instance.bvh->triangleCount() ? transformBox(instance.bvh->bounds(), instance.T_world_bvh)
                                                    : emptyBox();
  m_instanceBoxes[object] = instance.worldBox;
}

void CollisionScene::buildTopLevel() {
  std::vector<Aabb> boxes;
  std::vector<std::uint32_t> ids;
  for (std::uint32_t i = 0; i < m_instances.size(); ++i) {
    if (m_instances[i].bvh->triangleCount() == 0) continue;  // empty meshes never collide
    boxes.push_back(m_instanceBoxes[i]);
    ids.push_back(i);
  }
  m_top = buildBvh(boxes, {m_config.binCount, 1, m_config.traversalCost, 1});
  for (auto& id : m_top.primIds) id = ids[id];  // leaves name scene objects directly
}

RayHit CollisionScene::intersect(const Ray& ray) const noexcept {
  // Top-level boxes need only this; a scene whose top level is one leaf tests no box.
  const glm::vec3 invDirection = topHasBoxes() ? safeInverse(ray.direction) : glm::vec3(0.0f);
  float bestT = ray.tMax;
  const Instance* bestInstance = nullptr;
  std::uint32_t bestObject = kNoHit;
  MeshHit best;
  walkTop(
      m_top,
      [&](const BvhNode& n) { return intersectBox(ray.origin, invDirection, n.min, n.max, ray.tMin, bestT); },
      [&] { return bestT * kSlabExitMargin; },  // misses are +inf, never below the limit
      [&](std::uint32_t object) {
        const Instance& inst = m_instances[object];
        // `best` is written only by a hit nearer than bestT.
        if (inst.bvh->intersect(localRay(inst, ray), ray.tMin, best, bestT)) {
          bestT = best.t;
          bestInstance = &inst;
          bestObject = object;
        }
      });
  return bestInstance ? hitFrom(*bestInstance, bestObject, best) : RayHit{};
}

PreparedRay CollisionScene::localRay(const Instance& instance, const Ray& ray) noexcept {
  // The columns' sums grouped as glm's mat4 * vec4 and mat3 * vec3 group them, in four-lane
  // vectors: glm's own arithmetic goes one float at a time here.
  using V4 = float __attribute__((vector_size(16)));
  V4 m[4];
  static_assert(sizeof(m) == sizeof(instance.T_bvh_world), "glm::mat4 is four columns of four floats");
  std::memcpy(m, &instance.T_bvh_world, sizeof m);
  const glm::vec3& o = ray.origin;
  const glm::vec3& d = ray.direction;
  const V4 origin = (m[0] * o.x + m[1] * o.y) + (m[2] * o.z + m[3]);
  const V4 direction = (m[0] * d.x + m[1] * d.y) + m[2] * d.z;
  return {{origin[0], origin[1], origin[2]}, {direction[0], direction[1], direction[2]}};
}

RayHit CollisionScene::hitFrom(const Instance& instance, std::uint32_t object, const MeshHit& best) noexcept {
  RayHit result;
  result.object = object;
  result.t = best.t;
  result.triangle = best.triangle;
  result.u = best.u;
  result.v = best.v;
  result.frontFace = best.frontFace != instance.mirrored;
  return result;
}

void CollisionScene::intersect(std::span<const Ray> rays, std::span<RayHit> out) const noexcept {
  const std::size_t n = std::min(rays.size(), out.size());
  for (std::size_t first = 0; first < n; first += kMaxQueryBatch) {
    const std::size_t count = std::min<std::size_t>(kMaxQueryBatch, n - first);
    rayBatch(rays.subspan(first, count), out.subspan(first, count));
  }
}

SphereContact CollisionScene::sphereContact(const Sphere& sphere) const noexcept {
  if (!(sphere.radius_m > 0.0f)) return {};
  float bestD2 = sphere.radius_m * sphere.radius_m;  // world units
  const Instance* bestInstance = nullptr;
  std::uint32_t bestObject = kNoHit;
  MeshHit best;
  walkTop(
      m_top, [&](const BvhNode& n) { return distanceSquared(sphere.center, n.min, n.max); },
      [&] { return bestD2; },
      [&](std::uint32_t object) {
        const Instance& inst = m_instances[object];
        const glm::vec3 local(inst.T_bvh_world * glm::vec4(sphere.center, 1.0f));
        const float s2 = inst.scale * inst.scale;
        // `best` is written only by a point nearer than bestD2.
        if (inst.bvh->closestPoint(local, bestD2 / s2, best)) {
          bestD2 = best.t * s2;
          bestInstance = &inst;
          bestObject = object;
        }
      });
  return bestInstance ? contactFrom(sphere, *bestInstance, bestObject, best, bestD2) : SphereContact{};
}

SphereContact CollisionScene::contactFrom(const Sphere& sphere, const Instance& instance, std::uint32_t object,
                                          const MeshHit& best, float bestD2) const noexcept {
  SphereContact contact;
  const TrianglePositions tri = instance.bvh->slotTriangle(best.slot);
  glm::vec3 n = instance.normalToWorld * glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
  n = glm::normalize(instance.mirrored ? -n : n);
  contact.object = object;
  contact.triangle = best.triangle;
  contact.u = best.u;
  contact.v = best.v;
  contact.point = glm::vec3(instance.T_world_bvh * glm::vec4(best.point, 1.0f));
  contact.normal = n;
  contact.distance_m = std::sqrt(bestD2);
  const bool behind = glm::dot(sphere.center - contact.point, n) < 0.0f;
  contact.depth_m = sphere.radius_m + (behind ? contact.distance_m : -contact.distance_m);
  return contact;
}

void CollisionScene::sphereContacts(std::span<const Sphere> spheres, std::span<SphereContact> out) const noexcept {
  const std::size_t n = std::min(spheres.size(), out.size());
  for (std::size_t first = 0; first < n; first += kMaxQueryBatch) {
    const std::size_t count = std::min<std::size_t>(kMaxQueryBatch, n - first);
    sphereBatch(spheres.subspan(first, count), out.subspan(first, count));
  }
}

// A batch's (instance, query) pairs, found by one top-level walk per query; each instance's
// queries then go down its mesh BVH together. Fixed arrays: the haptic thread calls this.
struct CollisionScene::Candidates {
  struct Pair {
    std::uint32_t object, query;
  };
  static constexpr int kCapacity = 256;
  Pair pairs[kCapacity];
  int count = 0;
  bool overflow[kMaxQueryBatch] = {};  // that query touched too many instances: run it alone

  void add(std::uint32_t object, std::uint32_t query) noexcept {
    if (count < kCapacity) {
      pairs[count++] = {object, query};
    } else {
      overflow[query] = true;
    }
  }
  void sortByObject() noexcept {
    std::sort(pairs, pairs + count, [](const Pair& a, const Pair& b) { return a.object < b.object; });
  }
  /// Calls group(object, queries, n) for each instance with its queries.
  template <class Group>
  void forEachObject(Group&& group) const noexcept {
    for (int begin = 0; begin < count;) {
      const std::uint32_t object = pairs[begin].object;
      std::uint32_t queries[kMaxQueryBatch];
      int n = 0;
      for (; begin < count && pairs[begin].object == object; ++begin) queries[n++] = pairs[begin].query;
      group(object, queries, n);
    }
  }
};

void CollisionScene::rayBatch(std::span<const Ray> rays, std::span<RayHit> out) const noexcept {
  Candidates candidates;
  float bestT[kMaxQueryBatch];
  const Instance* bestInstance[kMaxQueryBatch] = {};
  std::uint32_t bestObject[kMaxQueryBatch];
  MeshHit best[kMaxQueryBatch];
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray& ray = rays[i];
    const glm::vec3 invDirection = topHasBoxes() ? safeInverse(ray.direction) : glm::vec3(0.0f);
    bestT[i] = ray.tMax;
    walkTop(
        m_top,
        [&](const BvhNode& node) { return intersectBox(ray.origin, invDirection, node.min, node.max, ray.tMin, bestT[i]); },
        [&] { return bestT[i] * kSlabExitMargin; },
        [&](std::uint32_t object) { candidates.add(object, std::uint32_t(i)); });
  }
  candidates.sortByObject();
  candidates.forEachObject([&](std::uint32_t object, const std::uint32_t* queries, int count) {
    const Instance& inst = m_instances[object];
    PreparedRay local[kMaxQueryBatch];
    float tMin[kMaxQueryBatch], tMax[kMaxQueryBatch];
    MeshHit hits[kMaxQueryBatch];
    for (int k = 0; k < count; ++k) {
      const Ray& ray = rays[queries[k]];
      local[k] = localRay(inst, ray);
      tMin[k] = ray.tMin;
      tMax[k] = bestT[queries[k]];
    }
    const auto n = std::size_t(count);
    const std::uint32_t found = inst.bvh->intersects({local, n}, {tMin, n}, {tMax, n}, {hits, n});
    for (int k = 0; k < count; ++k) {
      if (!(found >> k & 1u)) continue;
      const std::uint32_t i = queries[k];
      bestT[i] = hits[k].t;
      best[i] = hits[k];
      bestInstance[i] = &inst;
      bestObject[i] = object;
    }
  });
  for (std::size_t i = 0; i < rays.size(); ++i) {
    if (candidates.overflow[i]) {
      out[i] = intersect(rays[i]);
    } else {
      out[i] = bestInstance[i] ? hitFrom(*bestInstance[i], bestObject[i], best[i]) : RayHit{};
    }
  }
}

void CollisionScene::sphereBatch(std::span<const Sphere> spheres, std::span<SphereContact> out) const noexcept {
  Candidates candidates;
  float bestD2[kMaxQueryBatch];
  const Instance* bestInstance[kMaxQueryBatch] = {};
  std::uint32_t bestObject[kMaxQueryBatch];
  MeshHit best[kMaxQueryBatch];
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const Sphere& sphere = spheres[i];
    bestD2[i] = sphere.radius_m > 0.0f ? sphere.radius_m * sphere.radius_m : 0.0f;
    if (bestD2[i] == 0.0f) continue;
    walkTop(
        m_top, [&](const BvhNode& node) { return distanceSquared(sphere.center, node.min, node.max); },
        [&] { return bestD2[i]; }, [&](std::uint32_t object) { candidates.add(object, std::uint32_t(i)); });
  }
  candidates.sortByObject();
  candidates.forEachObject([&](std::uint32_t object, const std::uint32_t* queries, int count) {
    const Instance& inst = m_instances[object];
    const float s2 = inst.scale * inst.scale;
    glm::vec3 points[kMaxQueryBatch];
    float limits[kMaxQueryBatch];
    MeshHit hits[kMaxQueryBatch];
    for (int k = 0; k < count; ++k) {
      points[k] = glm::vec3(inst.T_bvh_world * glm::vec4(spheres[queries[k]].center, 1.0f));
      limits[k] = bestD2[queries[k]] / s2;
    }
    const auto n = std::size_t(count);
    const std::uint32_t found = inst.bvh->closestPoints({points, n}, {limits, n}, {hits, n});
    for (int k = 0; k < count; ++k) {
      if (!(found >> k & 1u)) continue;
      const std::uint32_t i = queries[k];
      bestD2[i] = limits[k] * s2;
      best[i] = hits[k];
      bestInstance[i] = &inst;
      bestObject[i] = object;
    }
  });
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    if (candidates.overflow[i]) {
      out[i] = sphereContact(spheres[i]);  // touched more instances than the batch holds
    } else {
      out[i] = bestInstance[i] ? contactFrom(spheres[i], *bestInstance[i], bestObject[i], best[i], bestD2[i])
                               : SphereContact{};
    }
  }
}

}  // namespace vt::collision
