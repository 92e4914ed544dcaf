#include "vt/collision/mesh_bvh.hpp"

#include <algorithm>

#include "kernels.hpp"
#include "vt/core/error.hpp"

namespace vt::collision {

MeshBvh::MeshBvh(const Mesh& mesh, const std::string& name, const BuildConfig& config, const glm::mat3& linear) {
  if (mesh.indices.size() % 3 != 0) {
    fail("collision: mesh '", name, "': index count ", mesh.indices.size(), " is not a multiple of 3");
  }
  // Boxes straight from the mesh; the leaf-ordered copy is made from the mesh again after the
  // build (no triangle array in between: fresh pages are much of the cost). The shared,
  // untransformed BVH (identity) skips the matrix and the second degeneracy test.
  const bool identity = linear == glm::mat3(1.0f);
  auto triangle = [&](std::size_t i) {
    const glm::vec3& p0 = mesh.vertices[mesh.indices[3 * i]].position;
    const glm::vec3& p1 = mesh.vertices[mesh.indices[3 * i + 1]].position;
    const glm::vec3& p2 = mesh.vertices[mesh.indices[3 * i + 2]].position;
    return identity ? TrianglePositions{p0, p1, p2} : TrianglePositions{linear * p0, linear * p1, linear * p2};
  };
  std::vector<std::uint32_t> ids;
  std::vector<Aabb> boxes;
  ids.reserve(mesh.triangleCount());
  boxes.reserve(mesh.triangleCount());
  for (std::size_t i = 0; i < mesh.triangleCount(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t index = mesh.indices[3 * i + std::size_t(k)];
      if (index >= mesh.vertices.size()) {
        fail("collision: mesh '", name, "': triangle ", i, " uses vertex ", index, " of ", mesh.vertices.size());
      }
    }
    const TrianglePositions t = triangle(i);
    // Judged in the mesh's own frame too, so a baked instance keeps exactly the same triangles.
    if (isDegenerate(mesh.vertices[mesh.indices[3 * i]].position, mesh.vertices[mesh.indices[3 * i + 1]].position,
                     mesh.vertices[mesh.indices[3 * i + 2]].position) ||
        (!identity && isDegenerate(t.p0, t.p1, t.p2))) {
      continue;
    }
    const Aabb box{glm::min(t.p0, glm::min(t.p1, t.p2)), glm::max(t.p0, glm::max(t.p1, t.p2))};
    ids.push_back(std::uint32_t(i));
    boxes.push_back(box);
  }
  BuildConfig leafLimited = config;  // wide nodes store leaf sizes in a byte
  leafLimited.maxLeafSize = std::min(config.maxLeafSize, kMaxWideLeafSize);
  const Bvh bvh = buildBvh(boxes, leafLimited);
  m_triangles.resize(ids.size());
  m_meshTriangle.resize(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    m_meshTriangle[i] = ids[bvh.primIds[i]];
    m_triangles[i] = triangle(m_meshTriangle[i]);
  }
  // Leaves index m_triangles directly (already in primIds order).
  m_nodes = collapseToWide(bvh);
  if (!bvh.empty()) m_bounds = {bvh.nodes[0].min, bvh.nodes[0].max};
}

Aabb MeshBvh::bounds() const noexcept { return m_bounds; }

bool MeshBvh::intersect(const PreparedRay& ray, float tMin, MeshHit& best, float tMax) const noexcept {
  return intersects({&ray, 1}, {&tMin, 1}, {&tMax, 1}, {&best, 1}) != 0;
}

std::uint32_t MeshBvh::intersects(std::span<const PreparedRay> rays, std::span<const float> tMin,
                                  std::span<float> tMax, std::span<MeshHit> best) const noexcept {
  const int count = int(std::min({rays.size(), tMin.size(), tMax.size(), best.size(), std::size_t(kMaxQueryBatch)}));
  if (m_nodes.empty() || count == 0) return 0;
  const std::uint32_t found = activeKernels().intersects(m_nodes.data(), m_triangles.data(), rays.data(), tMin.data(),
                                                         tMax.data(), best.data(), count);
  for (int i = 0; i < count; ++i) {
    if (found >> i & 1u) best[std::size_t(i)].triangle = m_meshTriangle[best[std::size_t(i)].slot];
  }
  return found;
}

bool MeshBvh::closestPoint(const glm::vec3& p, float maxDistanceSquared, MeshHit& best) const noexcept {
  return closestPoints({&p, 1}, {&maxDistanceSquared, 1}, {&best, 1}) != 0;
}

std::uint32_t MeshBvh::closestPoints(std::span<const glm::vec3> points, std::span<float> limits,
                                     std::span<MeshHit> best) const noexcept {
  const int count = int(std::min({points.size(), limits.size(), best.size(), std::size_t(kMaxQueryBatch)}));
  if (m_nodes.empty() || count == 0) return 0;
  const std::uint32_t found =
      activeKernels().closestPoints(m_nodes.data(), m_triangles.data(), points.data(), limits.data(), best.data(), count);
  for (int i = 0; i < count; ++i) {
    if (found >> i & 1u) best[std::size_t(i)].triangle = m_meshTriangle[best[std::size_t(i)].slot];
  }
  return found;
}

}  // namespace vt::collision
