#pragma once
// A wide BVH collapsed from the binary SAH tree: each node holds its kWidth children's boxes
// quantized to 8 bits per plane relative to the node's own box (Ylitie, Karras, Laine 2017),
// so a node is two cache lines instead of four. Random queries on large meshes wait on
// memory, one node per level; halving the bytes per node is what speeds them up. Decoding
// is exact (power-of-two scales) and rounded outward, so boxes stay conservative.
#include <cstdint>
#include <vector>

#include "vt/collision/bvh.hpp"
#include "vt/collision/huge_page_allocator.hpp"

namespace vt::collision {

/// Children per wide node (8: one AVX register, two SSE registers).
inline constexpr int kWidth = 8;
/// Largest leaf a wide node can reference (counts are bytes; kEmpty marks unused slots).
inline constexpr int kMaxWideLeafSize = 64;

/// One wide node: child box plane = origin[axis] + q * scale[axis], q in 0..255.
struct alignas(64) WideNode {
  static constexpr std::uint8_t kEmpty = 0xff;
  float origin[3];   // the node box's minimum corner
  float scale[3];    // a power of two per axis, so q * scale is exact
  std::uint8_t lo[3][kWidth];   // child minimum per axis, rounded down
  std::uint8_t hi[3][kWidth];   // child maximum per axis, rounded up
  std::uint32_t child[kWidth];  // inner: node index; leaf: first primitive (in primIds order)
  std::uint8_t count[kWidth];   // 0 = inner child, n > 0 = leaf of n primitives, kEmpty = none

  /// The decoded (conservative) box of child `i`.
  Aabb childBox(int i) const noexcept;
};
static_assert(sizeof(WideNode) == 128);

using WideNodes = std::vector<WideNode, HugePageAllocator<WideNode>>;

/// Collapses a binary BVH whose leaves hold at most kMaxWideLeafSize primitives (root = wide
/// node 0); subtrees of at most mergeLeafSize primitives (one contiguous primIds range)
/// become one leaf. A single-leaf tree becomes one node with one leaf child; an empty tree
/// gives no nodes. Setup threads.
WideNodes collapseToWide(const Bvh& binary, std::uint32_t mergeLeafSize = 0);

}  // namespace vt::collision
