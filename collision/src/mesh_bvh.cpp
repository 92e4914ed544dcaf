#include "vt/collision/mesh_bvh.hpp"

#include <algorithm>

#include "kernels.hpp"
#include "vt/core/error.hpp"

namespace vt::collision {

MeshBvh::MeshBvh(const Mesh& mesh, const std::string& name, const BuildConfig& config, const glm::mat3& linear) {
  if (mesh.indices.size() % 3 != 0) {
    fail("collision: mesh '", name, "': index count ", mesh.indices.size(), " is not a multiple of 3");
  }
  std::vector<TrianglePositions> tris;
  std::vector<std::uint32_t> ids;
  tris.reserve(mesh.triangleCount());
  ids.reserve(mesh.triangleCount());
  for (std::size_t i = 0; i < mesh.triangleCount(); ++i) {
    glm::vec3 p[3], q[3];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t index = mesh.indices[3 * i + std::size_t(k)];
      if (index >= mesh.vertices.size()) {
        fail("collision: mesh '", name, "': triangle ", i, " uses vertex ", index, " of ", mesh.vertices.size());
      }
      q[k] = mesh.vertices[index].position;
      p[k] = linear * q[k];
    }
    // Judged in the mesh's own frame so a baked instance keeps exactly the same triangles.
    if (isDegenerate(q[0], q[1], q[2]) || isDegenerate(p[0], p[1], p[2])) continue;
    tris.push_back({p[0], p[1], p[2]});
    ids.push_back(std::uint32_t(i));
  }
  std::vector<Aabb> boxes(tris.size());
  std::vector<glm::vec3> centers(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i) {
    const TrianglePositions& t = tris[i];
    boxes[i] = {glm::min(t.p0, glm::min(t.p1, t.p2)), glm::max(t.p0, glm::max(t.p1, t.p2))};
    centers[i] = (boxes[i].min + boxes[i].max) * 0.5f;
  }
  BuildConfig leafLimited = config;  // wide nodes store leaf sizes in a byte
  leafLimited.maxLeafSize = std::min(config.maxLeafSize, kMaxWideLeafSize);
  const Bvh bvh = buildBvh(boxes, centers, leafLimited);
  m_triangles.resize(tris.size());
  m_meshTriangle.resize(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i) {
    m_triangles[i] = tris[bvh.primIds[i]];
    m_meshTriangle[i] = ids[bvh.primIds[i]];
  }
  // Leaves index m_triangles directly (already in primIds order).
  m_nodes = collapseToWide(bvh);
  if (!bvh.empty()) m_bounds = {bvh.nodes[0].min, bvh.nodes[0].max};
}

Aabb MeshBvh::bounds() const noexcept { return m_bounds; }

bool MeshBvh::intersect(const PreparedRay& ray, float tMin, MeshHit& best, float tMax) const noexcept {
  if (m_nodes.empty() || !activeKernels().intersect(m_nodes.data(), m_triangles.data(), ray, tMin, tMax, best)) {
    return false;
  }
  best.triangle = m_meshTriangle[best.slot];
  return true;
}

bool MeshBvh::closestPoint(const glm::vec3& p, float maxDistanceSquared, MeshHit& best) const noexcept {
  if (m_nodes.empty() || !activeKernels().closestPoint(m_nodes.data(), m_triangles.data(), p, maxDistanceSquared, best)) {
    return false;
  }
  best.triangle = m_meshTriangle[best.slot];
  return true;
}

}  // namespace vt::collision
