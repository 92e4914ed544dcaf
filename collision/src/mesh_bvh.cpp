#include "vt/collision/mesh_bvh.hpp"

#include <algorithm>

#include "kernels.hpp"
#include "vt/core/error.hpp"

namespace vt::collision {

std::size_t floatNodesUpToTrianglesFor(int mergedLeafSize) noexcept {
  return std::size_t(32'768) * std::size_t(std::max(mergedLeafSize, 1));
}

MeshBvh::MeshBvh(const Mesh& mesh, const std::string& name, const BuildConfig& config, const glm::mat3& linear) {
  if (mesh.indices.size() % 3 != 0) {
    fail("collision: mesh '", name, "': index count ", mesh.indices.size(), " is not a multiple of 3");
  }
  // Boxes straight from the mesh; the leaf-ordered packs are made from the mesh again after the
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
  std::vector<Aabb, HugePageAllocator<Aabb>> boxes;  // 24 MB for 1M triangles: fewer page faults
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
  // Each leaf starts a pack, so a range of one pack split in two would take two: such ranges
  // stay leaves without binning, which is most of the nodes binned (figures in
  // docs/PERFORMANCE.md, "Where the goals stand, 2026-11-28, later that day").
  leafLimited.leafFloor = std::max(config.leafFloor, kPackLanes);
  const Bvh bvh = buildBvh(boxes, leafLimited);
  m_triangleCount = ids.size();
  const auto merged = std::uint32_t(std::clamp(
      config.mergedLeafSize > 0 ? config.mergedLeafSize : kDefaultMergedLeafSize, 1, kMaxWideLeafSize));
  const std::size_t floatNodesUpTo = config.floatNodesUpToTriangles == kFloatNodesByLeafSize
                                         ? floatNodesUpToTrianglesFor(int(merged))
                                         : config.floatNodesUpToTriangles;
  if (ids.size() <= floatNodesUpTo) {
    m_nodes = collapseToWide<WideNode>(bvh, merged);
  } else {
    m_quantizedNodes = collapseToWide<QuantizedWideNode>(bvh, merged);
  }
  // Calls f(count, child) on every leaf child of the nodes, in whichever format they are.
  auto forEachLeaf = [&](auto&& f) {
    auto visit = [&](auto& nodes) {
      for (auto& node : nodes) {
        for (int i = 0; i < kWidth; ++i) {
          if (node.count[i] != 0 && node.count[i] != WideNode::kEmpty) f(node.count[i], node.child[i]);
        }
      }
    };
    visit(m_nodes);
    visit(m_quantizedNodes);
  };
  // Each leaf starts a pack; slotOf maps leaf order (primIds) to slots, padding lanes between.
  std::vector<std::uint32_t> leafSize(ids.size(), 0);  // at each leaf's first primitive
  forEachLeaf([&](std::uint8_t count, std::uint32_t child) { leafSize[child] = count; });
  std::vector<std::uint32_t> slotOf(ids.size());
  std::uint32_t slot = 0;
  for (std::size_t i = 0; i < ids.size();) {
    const std::uint32_t count = leafSize[i];
    if (count == 0) fail("collision: mesh '", name, "': the BVH leaves do not cover primitive ", i);
    for (std::uint32_t k = 0; k < count; ++k) slotOf[i + k] = slot + k;
    slot += (count + kPackLanes - 1) / kPackLanes * kPackLanes;
    i += count;
  }
  // Each pack is made when its first lane is written (slots ascend in leaf order), so the
  // 47 MB of a 1M-triangle mesh's packs are written once instead of zeroed first by a resize.
  m_packs.reserve(slot / kPackLanes);
  // Leaf order visits the mesh's triangles out of order: each one's indices and vertices are
  // fetched ahead, the indices twice as far ahead as the vertices they name.
  constexpr std::size_t kAhead = 16;
  auto meshTriangleAt = [&](std::size_t i) { return ids[bvh.primIds[i]]; };
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (i + 2 * kAhead < ids.size()) __builtin_prefetch(&mesh.indices[3 * std::size_t(meshTriangleAt(i + 2 * kAhead))]);
    if (i + kAhead < ids.size()) {
      const std::uint32_t* corners = &mesh.indices[3 * std::size_t(meshTriangleAt(i + kAhead))];
      for (int k = 0; k < 3; ++k) __builtin_prefetch(&mesh.vertices[corners[k]].position);
    }
    const std::uint32_t meshTriangle = meshTriangleAt(i);
    const TrianglePositions t = triangle(meshTriangle);
    const glm::vec3 corners[3] = {t.p0, t.p1, t.p2};
    const std::uint32_t lane = slotOf[i] % kPackLanes;
    if (lane == 0) m_packs.emplace_back();
    TrianglePack& pack = m_packs.back();
    // Padding lanes repeat the leaf's first triangle: finite values, masked out by the kernels.
    const std::uint32_t fillEnd = lane == 0 ? kPackLanes : lane + 1;
    for (std::uint32_t l = lane; l < fillEnd; ++l) {
      for (int c = 0; c < 9; ++c) pack.v[c][l] = corners[c / 3][c % 3];
      pack.triangle[l] = l == lane ? meshTriangle : kNoHit;
    }
  }
  forEachLeaf([&](std::uint8_t, std::uint32_t& child) { child = slotOf[child]; });
  if (!bvh.empty()) m_bounds = {bvh.nodes[0].min, bvh.nodes[0].max};
  const std::size_t bytes = m_nodes.size() * sizeof(WideNode) + m_quantizedNodes.size() * sizeof(QuantizedWideNode) +
                            m_packs.size() * sizeof(TrianglePack);
  // The defaults (BuildConfig): one by one against in turns (results/archive/
  // haptics-2026-11-28-batches/crossover-*.json: Zen 3, 512 KB L2, 32 MB L3; these BVHs take
  // about 50 bytes a triangle): 12-sphere batches 1.15x at 0.47 MB, 1.08x at 1.5 MB, 0.93x at
  // 4.3 MB; 16-ray batches 1.48x at 0.47 MB, 1.31x at 4.3 MB, 0.96x at 7.8 MB (1.03x in an
  // earlier run), 0.95x at 14 MB, 0.91x at 29 MB, 0.78x at 49 MB. A ray's turn carries more
  // state than a point's, so rays break even on a larger tree. Those trees had byte nodes; with
  // float nodes (under floatNodesUpToTriangles) 12-sphere batches measured 1.07x on 32k and 0.95x
  // on 89k triangles (results/archive/haptics-2026-11-28-float-nodes/crossover-*.json).
  m_raysInTurns = bytes >= config.raysInTurnsFromBytes;
  m_pointsInTurns = bytes >= config.pointsInTurnsFromBytes;
}

TrianglePositions MeshBvh::slotTriangle(std::uint32_t slot) const noexcept {
  const TrianglePack& pack = m_packs[slot / kPackLanes];
  const std::uint32_t lane = slot % kPackLanes;
  glm::vec3 p[3];
  for (int c = 0; c < 9; ++c) p[c / 3][c % 3] = pack.v[c][lane];
  return {p[0], p[1], p[2]};
}

Aabb MeshBvh::bounds() const noexcept { return m_bounds; }

template <class F>
auto MeshBvh::withNodes(F&& f) const noexcept {
  const QueryKernels& kernels = activeKernels();
  return m_quantizedNodes.empty() ? f(kernels.floatNodes, m_nodes.data())
                                  : f(kernels.quantizedNodes, m_quantizedNodes.data());
}

bool MeshBvh::intersect(const PreparedRay& ray, float tMin, MeshHit& best, float tMax) const noexcept {
  return hasNodes() && withNodes([&](const auto& walks, const auto* nodes) {
           return walks.intersect(nodes, m_packs.data(), ray, tMin, tMax, best);
         });
}

std::uint32_t MeshBvh::intersects(std::span<const PreparedRay> rays, std::span<const float> tMin,
                                  std::span<float> tMax, std::span<MeshHit> best) const noexcept {
  const int count = int(std::min({rays.size(), tMin.size(), tMax.size(), best.size(), std::size_t(kMaxQueryBatch)}));
  if (!hasNodes() || count == 0) return 0;
  return withNodes([&](const auto& walks, const auto* nodes) {
    if (m_raysInTurns) return walks.intersects(nodes, m_packs.data(), rays.data(), tMin.data(), tMax.data(), best.data(), count);
    std::uint32_t found = 0;
    for (std::size_t i = 0; i < std::size_t(count); ++i) {
      if (walks.intersect(nodes, m_packs.data(), rays[i], tMin[i], tMax[i], best[i])) {
        tMax[i] = best[i].t;
        found |= 1u << i;
      }
    }
    return found;
  });
}

bool MeshBvh::closestPoint(const glm::vec3& p, float maxDistanceSquared, MeshHit& best) const noexcept {
  return hasNodes() && withNodes([&](const auto& walks, const auto* nodes) {
           return walks.closestPoint(nodes, m_packs.data(), p, maxDistanceSquared, best);
         });
}

std::uint32_t MeshBvh::closestPoints(std::span<const glm::vec3> points, std::span<float> limits,
                                     std::span<MeshHit> best) const noexcept {
  const int count = int(std::min({points.size(), limits.size(), best.size(), std::size_t(kMaxQueryBatch)}));
  if (!hasNodes() || count == 0) return 0;
  return withNodes([&](const auto& walks, const auto* nodes) {
    if (m_pointsInTurns) return walks.closestPoints(nodes, m_packs.data(), points.data(), limits.data(), best.data(), count);
    std::uint32_t found = 0;
    for (std::size_t i = 0; i < std::size_t(count); ++i) {
      if (walks.closestPoint(nodes, m_packs.data(), points[i], limits[i], best[i])) {
        limits[i] = best[i].t;
        found |= 1u << i;
      }
    }
    return found;
  });
}

}  // namespace vt::collision
