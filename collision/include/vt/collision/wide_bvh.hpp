#pragma once
// A wide BVH collapsed from the binary SAH tree, in one of two node formats. WideNode holds its
// kWidth children's boxes as float planes, so a child test is a subtraction and a
// multiplication per plane. QuantizedWideNode holds each plane as a byte relative to the node's
// box (Ylitie, Karras, Laine 2017): half the bytes (two cache lines), for a conversion and a
// multiply-add more per plane. Side by side on Zen 3 (docs/PERFORMANCE.md) float planes made
// queries 1.04 - 1.09x faster on 10k - 90k triangles and were equal on 1M, where the nodes
// still fit its 32 MB L3; on a Zen 1 host with an 8 MB L3, float planes read from a side array
// (192 more bytes a node) cost 1M-triangle rays 28 % (a scratch program, not stored). On Zen 5
// float nodes won or tied up to about 4 MB of them and lost at 8.6 MB. So trees whose float nodes
// stay under about 4 MB use float planes and larger ones bytes
// (BuildConfig::floatNodesUpToTriangles, floatNodesUpToTrianglesFor in mesh_bvh.hpp).
#include <cstdint>
#include <vector>

#include "vt/collision/bvh.hpp"
#include "vt/collision/huge_page_allocator.hpp"

namespace vt::collision {

/// Children per wide node (8: one AVX register, two SSE registers).
inline constexpr int kWidth = 8;
/// Largest leaf a wide node can reference (counts are bytes; kEmpty marks unused slots).
inline constexpr int kMaxWideLeafSize = 64;

/// One wide node: its children's boxes as float planes, one row of kWidth per axis and side.
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

/// The same node with child box plane = origin[axis] + q * scale[axis], q in 0..255.
struct alignas(64) QuantizedWideNode {
  static constexpr std::uint8_t kEmpty = WideNode::kEmpty;
  float origin[3];   // the node box's minimum corner
  float scale[3];    // a power of two per axis, so q * scale is exact
  std::uint8_t lo[3][kWidth];   // child minimum per axis, rounded down
  std::uint8_t hi[3][kWidth];   // child maximum per axis, rounded up
  std::uint32_t child[kWidth];
  std::uint8_t count[kWidth];

  /// The decoded (conservative) box of child `i`.
  Aabb childBox(int i) const noexcept;
};
static_assert(sizeof(QuantizedWideNode) == 128);

using WideNodes = std::vector<WideNode, HugePageAllocator<WideNode>>;
using QuantizedWideNodes = std::vector<QuantizedWideNode, HugePageAllocator<QuantizedWideNode>>;

/// Collapses a binary BVH whose leaves hold at most kMaxWideLeafSize primitives (root = wide
/// node 0); subtrees of at most mergeLeafSize primitives (one contiguous primIds range)
/// become one leaf. A single-leaf tree becomes one node with one leaf child; an empty tree
/// gives no nodes. Node: WideNode or QuantizedWideNode. Setup threads.
template <class Node = WideNode>
std::vector<Node, HugePageAllocator<Node>> collapseToWide(const Bvh& binary, std::uint32_t mergeLeafSize = 0);

}  // namespace vt::collision
