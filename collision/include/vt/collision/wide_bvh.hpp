#pragma once
// A wide BVH collapsed from the binary SAH tree: each node holds its kWidth children's boxes
// as float planes, one row of kWidth per axis and side, so a child test is a subtraction and
// a multiplication per plane. (8-bit planes relative to the node's box (Ylitie, Karras, Laine
// 2017) halve a node to two cache lines but cost a conversion and a multiply-add per plane;
// measured side by side on Zen 3 (docs/PERFORMANCE.md), float planes were 1.07 - 1.11x faster
// on meshes of 10k - 90k triangles and equal on 1M, where the nodes stay in the last-level
// cache either way.)
#include <cstdint>
#include <vector>

#include "vt/collision/bvh.hpp"
#include "vt/collision/huge_page_allocator.hpp"

namespace vt::collision {

/// Children per wide node (8: one AVX register, two SSE registers).
inline constexpr int kWidth = 8;
/// Largest leaf a wide node can reference (counts are bytes; kEmpty marks unused slots).
inline constexpr int kMaxWideLeafSize = 64;

/// One wide node: its children's boxes as planes, kWidth lanes per axis and side.
struct alignas(64) WideNode {
  static constexpr std::uint8_t kEmpty = 0xff;
  float lo[3][kWidth];          // child minima per axis (unused slots: the first child's)
  float hi[3][kWidth];          // child maxima per axis
  std::uint32_t child[kWidth];  // inner: node index; leaf: first primitive (in primIds order)
  std::uint8_t count[kWidth];   // 0 = inner child, n > 0 = leaf of n primitives, kEmpty = none

  /// The box of child `i`.
  Aabb childBox(int i) const noexcept;
};
static_assert(sizeof(WideNode) == 256);

using WideNodes = std::vector<WideNode, HugePageAllocator<WideNode>>;

/// Collapses a binary BVH whose leaves hold at most kMaxWideLeafSize primitives (root = wide
/// node 0); subtrees of at most mergeLeafSize primitives (one contiguous primIds range)
/// become one leaf. A single-leaf tree becomes one node with one leaf child; an empty tree
/// gives no nodes. Setup threads.
WideNodes collapseToWide(const Bvh& binary, std::uint32_t mergeLeafSize = 0);

}  // namespace vt::collision
