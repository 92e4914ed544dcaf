#include "vt/collision/mesh_bvh.hpp"

#include <cmath>

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
  m_bvh = buildBvh(boxes, centers, config);
  m_triangles.resize(tris.size());
  m_meshTriangle.resize(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i) {
    m_triangles[i] = tris[m_bvh.primIds[i]];
    m_meshTriangle[i] = ids[m_bvh.primIds[i]];
  }
  // Leaves now index triangles directly; primIds is no longer needed.
  std::vector<std::uint32_t>().swap(m_bvh.primIds);
}

Aabb MeshBvh::bounds() const noexcept {
  if (m_bvh.empty()) return {};
  return {m_bvh.nodes[0].min, m_bvh.nodes[0].max};
}

bool MeshBvh::intersect(const PreparedRay& ray, float tMin, MeshHit& best, float tMax) const noexcept {
  if (m_bvh.empty()) return false;
  const BvhNode* nodes = m_bvh.nodes.data();
  if (intersectBox(ray, nodes[0].min, nodes[0].max, tMin, tMax) > tMax) return false;
  std::uint32_t stack[kTraversalStackSize];
  int top = 0;
  std::uint32_t current = 0;
  bool found = false;
  for (;;) {
    const BvhNode& node = nodes[current];
    if (node.isLeaf()) {
      for (std::uint32_t i = node.index, end = node.index + node.count; i < end; ++i) {
        const TrianglePositions& tri = m_triangles[i];
        float t, u, v;
        if (intersectTriangle(ray, tri.p0, tri.p1, tri.p2, tMin, tMax, t, u, v)) {
          tMax = t;
          best.t = t;
          best.u = u;
          best.v = v;
          best.slot = i;
          found = true;
        }
      }
    } else {
      const std::uint32_t left = node.index, right = node.index + 1;
      float tl = intersectBox(ray, nodes[left].min, nodes[left].max, tMin, tMax);
      float tr = intersectBox(ray, nodes[right].min, nodes[right].max, tMin, tMax);
      const bool hitL = tl <= tMax, hitR = tr <= tMax;
      if (hitL && hitR) {
        const bool leftFirst = tl <= tr;
        if (top < kTraversalStackSize) stack[top++] = leftFirst ? right : left;
        current = leftFirst ? left : right;
        continue;
      }
      if (hitL || hitR) {
        current = hitL ? left : right;
        continue;
      }
    }
    if (top == 0) break;
    current = stack[--top];
  }
  if (found) best.triangle = m_meshTriangle[best.slot];
  return found;
}

bool MeshBvh::closestPoint(const glm::vec3& p, float maxDistanceSquared, MeshHit& best) const noexcept {
  if (m_bvh.empty()) return false;
  const BvhNode* nodes = m_bvh.nodes.data();
  float bestD2 = maxDistanceSquared;
  if (distanceSquared(p, nodes[0].min, nodes[0].max) >= bestD2) return false;
  struct Entry {
    std::uint32_t node;
    float d2;
  };
  Entry stack[kTraversalStackSize];
  int top = 0;
  std::uint32_t current = 0;
  bool found = false;
  for (;;) {
    const BvhNode& node = nodes[current];
    if (node.isLeaf()) {
      for (std::uint32_t i = node.index, end = node.index + node.count; i < end; ++i) {
        const TrianglePositions& tri = m_triangles[i];
        float u, v;
        const glm::vec3 q = closestPointOnTriangle(p, tri.p0, tri.p1, tri.p2, u, v);
        const glm::vec3 d = q - p;
        const float d2 = glm::dot(d, d);
        if (d2 < bestD2) {
          bestD2 = d2;
          best = {kNoHit, i, d2, u, v, q};
          found = true;
        }
      }
    } else {
      const std::uint32_t left = node.index, right = node.index + 1;
      const float dl = distanceSquared(p, nodes[left].min, nodes[left].max);
      const float dr = distanceSquared(p, nodes[right].min, nodes[right].max);
      const bool hitL = dl < bestD2, hitR = dr < bestD2;
      if (hitL && hitR) {
        const bool leftFirst = dl <= dr;
        if (top < kTraversalStackSize) stack[top++] = {leftFirst ? right : left, leftFirst ? dr : dl};
        current = leftFirst ? left : right;
        continue;
      }
      if (hitL || hitR) {
        current = hitL ? left : right;
        continue;
      }
    }
    // Pop, skipping nodes that the improved best has ruled out since they were pushed.
    bool next = false;
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.d2 < bestD2) {
        current = e.node;
        next = true;
        break;
      }
    }
    if (!next) break;
  }
  if (found) best.triangle = m_meshTriangle[best.slot];
  return found;
}

}  // namespace vt::collision
