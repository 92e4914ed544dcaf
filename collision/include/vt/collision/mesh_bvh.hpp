#pragma once
// One mesh's BVH with its triangles stored in leaf order. Immutable after construction and
// shared read-only by any number of threads (and instances).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "vt/collision/bvh.hpp"
#include "vt/collision/huge_page_allocator.hpp"
#include "vt/collision/query.hpp"
#include "vt/collision/triangle.hpp"
#include "vt/collision/wide_bvh.hpp"
#include "vt/scene/mesh.hpp"

namespace vt::collision {

/// One triangle's vertices.
struct TrianglePositions {
  glm::vec3 p0, p1, p2;
};

/// Lanes of a TrianglePack: leaves are tested kPackLanes triangles at a time.
inline constexpr int kPackLanes = 4;

/// The largest binary subtree (in triangles) a mesh BVH makes one leaf by default: on large
/// meshes a wide node visit waits on memory longer than testing a few more packs takes. 32 for
/// every kernel set since nearest-point leaves skip the triangles whose boxes are out of reach
/// (before that, 16 for SSE2 and AVX2, whose point queries lost 10 % with 32). Both trees in one
/// process on Zen 5, 32 against 16: AVX2 kernels' rays 1.04 - 1.18x on 1M triangles and 1.11 -
/// 1.15x on 90k, spheres 1.00 - 1.11x and 1.05 - 1.07x (0.95x on 10k); SSE2 rays 1.09 - 1.12x
/// on 1M (docs/PERFORMANCE.md, "Leaves of 32 on every machine").
inline constexpr int kDefaultMergedLeafSize = 32;

/// The most triangles a mesh BVH with merged leaves of `mergedLeafSize` gives float nodes by
/// default (BuildConfig::floatNodesUpToTriangles): 32 768 per leaf triangle, float nodes of about
/// 4 MB (a wide node per about twice the leaf size in triangles on the sphere). Above that, byte
/// nodes: where float nodes outgrow the caches, their decode is cheaper than their misses. On Zen 5
/// (32 MB L3), float against byte nodes in one process: 16-triangle leaves (AVX2 kernels) on 490k
/// triangles (4.2 MB of float nodes) rays 1.05x, spheres 1.05x, on 1M (8.6 MB) rays 0.93x, spheres
/// 0.97x; 32-triangle leaves (AVX-512) on 490k rays 1.03x, spheres 1.04x, on 1M (3.4 MB) rays
/// 1.00 - 1.01x, spheres 1.00 - 1.02x, builds 1.03 - 1.05x (docs/PERFORMANCE.md).
std::size_t floatNodesUpToTrianglesFor(int mergedLeafSize) noexcept;

/// kPackLanes triangles' vertices as structure of arrays (one SIMD load per coordinate).
struct alignas(16) TrianglePack {
  float v[9][kPackLanes];                 // p0.x p0.y p0.z p1.x ... p2.z, lane = triangle
  std::uint32_t triangle[kPackLanes];     // mesh triangle index; kNoHit: padding lane
};

/// Result of a query in the mesh's own frame.
struct MeshHit {
  std::uint32_t triangle = kNoHit;  // mesh triangle index
  std::uint32_t slot = kNoHit;      // pack * kPackLanes + lane (see slotTriangle)
  float t = 0.0f;       // ray: distance in |direction| units; point: squared distance
  float u = 0.0f, v = 0.0f;
  glm::vec3 point{0.0f};  // point queries only
  bool frontFace = false;  // ray queries only: the counter-clockwise side was met (mesh frame)
};

/// One mesh's wide BVH and leaf-ordered triangles; const queries from any thread.
class MeshBvh {
 public:
  MeshBvh() = default;
  /// Builds over `mesh` with vertices mapped by `linear` (identity normally; a baked scale
  /// for non-similarity instances). Degenerate and non-finite triangles are left out (no
  /// surface to touch); out-of-range indices throw vt::Error naming `name`. Setup threads.
  MeshBvh(const Mesh& mesh, const std::string& name, const BuildConfig& config = {},
          const glm::mat3& linear = glm::mat3(1.0f));

  /// Closest hit with t in (tMin, tMax); updates tMax-style via `best` (kNoHit = none yet).
  bool intersect(const PreparedRay& ray, float tMin, MeshHit& best, float tMax) const noexcept;
  /// Up to kMaxQueryBatch intersect queries: on large BVHs walked in turns (see closestPoints),
  /// on small ones one after another. tMax[i]: limit in, nearest hit out. Bit i of the result:
  /// ray i hit.
  std::uint32_t intersects(std::span<const PreparedRay> rays, std::span<const float> tMin, std::span<float> tMax,
                           std::span<MeshHit> best) const noexcept;
  /// Nearest surface point with squared distance < maxDistanceSquared, improving `best`.
  bool closestPoint(const glm::vec3& p, float maxDistanceSquared, MeshHit& best) const noexcept;
  /// Up to kMaxQueryBatch closestPoint queries: on large BVHs walked in turns, one node or leaf
  /// each (faster than one by one: their memory waits overlap), on BVHs that stay in cache one
  /// after another (the turns cost more than they save there). limits[i]: squared search radius
  /// in, nearest squared distance out. Bit i of the result: query i found a point.
  std::uint32_t closestPoints(std::span<const glm::vec3> points, std::span<float> limits,
                              std::span<MeshHit> best) const noexcept;

  /// Bounds in the (possibly baked) mesh frame.
  Aabb bounds() const noexcept;
  /// Triangles in the BVH (degenerate ones are left out).
  std::size_t triangleCount() const noexcept { return m_triangleCount; }
  /// Slots in the packs: triangleCount() plus the unused lanes that pad each leaf to whole packs.
  std::size_t slotCount() const noexcept { return m_packs.size() * kPackLanes; }
  /// The wide nodes queries walk (for tests and statistics), in the format the BVH's size chose
  /// (BuildConfig::floatNodesUpToTriangles): float planes here, or bytes in quantizedNodes(); the
  /// other is empty. A leaf child's slots are child .. child + count - 1, its first slot the
  /// first lane of a pack.
  std::span<const WideNode> nodes() const noexcept { return m_nodes; }
  std::span<const QuantizedWideNode> quantizedNodes() const noexcept { return m_quantizedNodes; }
  /// Vertices of the triangle in a slot (as a hit reports in MeshHit::slot).
  TrianglePositions slotTriangle(std::uint32_t slot) const noexcept;

 private:
  // Calls f(walks, nodes) with the kernels and nodes of the format this BVH holds.
  template <class F>
  auto withNodes(F&& f) const noexcept;
  bool hasNodes() const noexcept { return !m_nodes.empty() || !m_quantizedNodes.empty(); }

  WideNodes m_nodes;
  QuantizedWideNodes m_quantizedNodes;
  Aabb m_bounds{};
  std::size_t m_triangleCount = 0;
  std::vector<TrianglePack, HugePageAllocator<TrianglePack>> m_packs;  // leaf order, each leaf whole packs
  bool m_raysInTurns = false, m_pointsInTurns = false;  // batches walk in turns (see mesh_bvh.cpp)
};

/// Queries MeshBvh::intersects/closestPoints walk together (two hands' contact points fit).
inline constexpr int kMaxQueryBatch = 16;

/// Traversal stack depth of the binary top level; the builder keeps trees shallower.
inline constexpr int kTraversalStackSize = 64;
/// Wide traversal pushes at most kWidth - 1 net entries per level of a tree at most 64 deep.
inline constexpr int kWideStackSize = kWidth * kTraversalStackSize;

}  // namespace vt::collision
