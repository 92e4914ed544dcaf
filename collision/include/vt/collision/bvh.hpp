#pragma once
// A binary BVH that knows nothing about primitives: the builder takes a span of boxes
// (madmann91/bvh style); queries live next to the primitives they test.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "vt/collision/huge_page_allocator.hpp"
#include "vt/scene/mesh.hpp"

namespace vt::collision {

/// 32-byte flattened node. Leaf: count > 0 primitives from primIds[index]. Inner: count == 0,
/// children at nodes[index] and nodes[index + 1] (siblings are adjacent).
struct BvhNode {
  glm::vec3 min;
  std::uint32_t index;
  glm::vec3 max;
  std::uint32_t count;

  bool isLeaf() const noexcept { return count != 0; }
};
static_assert(sizeof(BvhNode) == 32);

/// BuildConfig::floatNodesUpToTriangles' default: the limit suited to the tree's leaf size.
inline constexpr std::size_t kFloatNodesByLeafSize = std::numeric_limits<std::size_t>::max() - 1;

/// Binned SAH settings, and how a mesh BVH walks batches; defaults suit triangle meshes.
struct BuildConfig {
  int binCount = 16;
  int maxLeafSize = 8;
  float traversalCost = 2.0f;  // one wide-node visit vs one primitive test (measured best)
  /// Ranges of at most this many primitives become leaves without an SAH test (capped at
  /// maxLeafSize; 1: the SAH decides every range).
  int leafFloor = 1;
  /// A mesh BVH of at least this many bytes walks batched rays / points in turns, one node or
  /// leaf each (their waits on memory overlap); smaller ones, which stay in cache, answer a
  /// batch one query after another. 0: always in turns. Defaults measured: mesh_bvh.cpp.
  std::size_t raysInTurnsFromBytes = std::size_t(8) << 20;
  std::size_t pointsInTurnsFromBytes = std::size_t(2) << 20;
  /// A mesh BVH over at most this many triangles gives its wide nodes float planes; a larger
  /// one stores each plane as a byte (half the bytes, a little more work a node: wide_bvh.hpp).
  /// 0: always bytes. The default, kFloatNodesByLeafSize: floatNodesUpToTrianglesFor(the merged
  /// leaf size) (mesh_bvh.hpp), which keeps float nodes under about 4 MB.
  std::size_t floatNodesUpToTriangles = kFloatNodesByLeafSize;
  /// A mesh BVH makes each binary subtree of at most this many triangles one wide-node leaf
  /// (up to kMaxWideLeafSize). 0: kDefaultMergedLeafSize (mesh_bvh.hpp).
  int mergedLeafSize = 0;
};

/// Nodes (root = nodes[0], children always after their parent) and primitive order.
struct Bvh {
  std::vector<BvhNode, HugePageAllocator<BvhNode>> nodes;  // tens of MB on large meshes: 2 MiB pages fault less
  std::vector<std::uint32_t> primIds;

  bool empty() const noexcept { return nodes.empty(); }
};

/// Builds with binned SAH over `boxes`, split by box centres. Setup threads only.
Bvh buildBvh(std::span<const Aabb> boxes, const BuildConfig& config = {});

/// Smallest box holding both.
inline Aabb merge(const Aabb& a, const Aabb& b) noexcept { return {glm::min(a.min, b.min), glm::max(a.max, b.max)}; }
/// An inverted box that merge() treats as empty.
inline Aabb emptyBox() noexcept { return {glm::vec3(3.4e38f), glm::vec3(-3.4e38f)}; }
/// Half surface area (the SAH only compares areas).
inline float halfArea(const Aabb& b) noexcept {
  const glm::vec3 e = glm::max(b.max - b.min, glm::vec3(0.0f));
  return e.x * e.y + e.y * e.z + e.z * e.x;
}
/// Squared distance from a point to a box (0 inside).
inline float distanceSquared(const glm::vec3& p, const glm::vec3& bmin, const glm::vec3& bmax) noexcept {
  const glm::vec3 d = glm::max(glm::max(bmin - p, p - bmax), glm::vec3(0.0f));
  return glm::dot(d, d);
}

}  // namespace vt::collision
