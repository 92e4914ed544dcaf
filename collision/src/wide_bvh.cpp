#include "vt/collision/wide_bvh.hpp"

#include <algorithm>

#include "vt/core/error.hpp"

namespace vt::collision {
namespace {

// One axis of up to kWidth child boxes; empty slots repeat the first child's planes, finite
// values that the kernels mask out.
void storeAxis(WideNode& w, int axis, const float* childLo, const float* childHi, int count) noexcept {
  for (int i = 0; i < kWidth; ++i) {
    w.lo[axis][i] = childLo[i < count ? i : 0];
    w.hi[axis][i] = childHi[i < count ? i : 0];
  }
}

// Per binary node, the primitives under it as one range of primIds, or {0, 0} when the
// subtree is larger than the merge limit (or, for a builder that does not keep subtrees
// contiguous, not one range): such subtrees stay inner nodes.
struct Subtree {
  std::uint32_t first = 0, count = 0;
};

struct Collapse {
  const Bvh& binary;
  std::vector<Subtree> merged;  // per binary node
  WideNodes& out;

  bool isLeaf(std::uint32_t node) const noexcept { return merged[node].count != 0; }
};

std::uint32_t collapse(const Collapse& c, std::uint32_t binaryNode) {
  const Bvh& binary = c.binary;
  WideNodes& out = c.out;
  // Open the largest inner children until the node is full (SAH: big boxes are hit most).
  std::uint32_t slots[kWidth];
  float areas[kWidth];  // each slot's half area, taken once
  auto place = [&](int i, std::uint32_t node) {
    const BvhNode& n = binary.nodes[node];
    slots[i] = node;
    areas[i] = halfArea({n.min, n.max});
  };
  place(0, binaryNode);
  int count = 1;
  const BvhNode& root = binary.nodes[binaryNode];
  if (!c.isLeaf(binaryNode)) {
    place(0, root.index);
    place(1, root.index + 1);
    count = 2;
  }
  // Opens the largest child that `openable` accepts; false when there is none.
  auto openLargest = [&](auto&& openable) {
    int best = -1;
    float bestArea = -1.0f;
    for (int i = 0; i < count; ++i) {
      if (areas[i] > bestArea && openable(slots[i])) best = i, bestArea = areas[i];
    }
    if (best < 0) return false;
    const std::uint32_t opened = binary.nodes[slots[best]].index;
    place(best, opened);
    place(count++, opened + 1);
    return true;
  };
  while (count < kWidth && openLargest([&](std::uint32_t node) { return !c.isLeaf(node); })) {
  }
  // Slots left over (every child is a merged leaf): split the largest leaves back into the
  // subtrees they were merged from. A node visit costs the same however many slots are in
  // use, and a query then tests only the smaller leaves it reaches (measured on 1M triangles:
  // single rays 7 %, spheres 11 % faster).
  while (count < kWidth && openLargest([&](std::uint32_t node) { return !binary.nodes[node].isLeaf(); })) {
  }
  const auto index = std::uint32_t(out.size());
  out.push_back({});
  {
    WideNode& w = out[index];
    for (int axis = 0; axis < 3; ++axis) {
      float lo[kWidth] = {}, hi[kWidth] = {};
      for (int i = 0; i < count; ++i) lo[i] = binary.nodes[slots[i]].min[axis], hi[i] = binary.nodes[slots[i]].max[axis];
      storeAxis(w, axis, lo, hi, count);
    }
    for (int i = 0; i < kWidth; ++i) {
      w.child[i] = 0;
      w.count[i] = WideNode::kEmpty;
    }
  }
  for (int i = 0; i < count; ++i) {
    if (c.isLeaf(slots[i])) {
      const Subtree leaf = c.merged[slots[i]];
      if (leaf.count > std::uint32_t(kMaxWideLeafSize)) fail("bvh: leaf of ", leaf.count, " primitives is too large");
      out[index].child[i] = leaf.first;
      out[index].count[i] = std::uint8_t(leaf.count);
    } else {
      const std::uint32_t child = collapse(c, slots[i]);  // may reallocate `out`
      out[index].child[i] = child;
      out[index].count[i] = 0;
    }
  }
  return index;
}

}  // namespace

Aabb WideNode::childBox(int i) const noexcept {
  Aabb box;
  for (int a = 0; a < 3; ++a) box.min[a] = lo[a][i], box.max[a] = hi[a][i];
  return box;
}

WideNodes collapseToWide(const Bvh& binary, std::uint32_t mergeLeafSize) {
  WideNodes out;
  if (binary.empty()) return out;
  Collapse c{binary, std::vector<Subtree>(binary.nodes.size()), out};
  // Children come after their parents: one backward pass sees children first.
  for (std::size_t i = binary.nodes.size(); i-- > 0;) {
    const BvhNode& n = binary.nodes[i];
    if (n.isLeaf()) {
      c.merged[i] = {n.index, n.count};
      continue;
    }
    const Subtree a = c.merged[n.index], b = c.merged[n.index + 1];
    const std::uint32_t total = a.count + b.count;
    if (a.count == 0 || b.count == 0 || total > mergeLeafSize) continue;
    if (a.first + a.count == b.first) {
      c.merged[i] = {a.first, total};
    } else if (b.first + b.count == a.first) {
      c.merged[i] = {b.first, total};
    }
  }
  out.reserve(binary.nodes.size() / 2 + 1);  // an upper bound; untouched pages cost nothing
  collapse(c, 0);
  return out;
}

}  // namespace vt::collision
