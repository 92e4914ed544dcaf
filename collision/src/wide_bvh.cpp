#include "vt/collision/wide_bvh.hpp"

#include <algorithm>
#include <cmath>

#include "vt/core/error.hpp"

namespace vt::collision {
namespace {

// The kernels decode with the same expression: q * scale is exact, so the one rounding of
// the sum is the same with or without FMA.
float decode(float origin, float scale, std::uint8_t q) noexcept { return origin + float(q) * scale; }

// Quantizes one axis of up to kWidth child boxes relative to [lo, hi], rounding outward and
// checking each plane by decoding it; a scale that cannot hold a plane is doubled.
void setPlanes(QuantizedWideNode& w, int axis, const float* childLo, const float* childHi, int count) noexcept {
  float nodeLo = childLo[0], nodeHi = childHi[0];
  for (int i = 1; i < count; ++i) nodeLo = std::min(nodeLo, childLo[i]), nodeHi = std::max(nodeHi, childHi[i]);
  const float extent = nodeHi - nodeLo;
  float scale = extent > 0.0f ? std::ldexp(1.0f, std::ilogb(extent / 255.0f) + 1) : 1.0f;
  scale = std::clamp(scale, std::ldexp(1.0f, -149), std::ldexp(1.0f, 127));
  for (;;) {
    // Dividing by a power of two is multiplying by its exact reciprocal (representable from
    // 2^-126 on; below it, divide). Both offsets are >= 0 (nodeLo is the least of the
    // children's minima), so floor is truncation; clamped first, so the conversion is defined.
    const float inverse = scale >= std::ldexp(1.0f, -126) ? 1.0f / scale : 0.0f;
    auto units = [&](float offset) { return std::min(inverse != 0.0f ? offset * inverse : offset / scale, 255.0f); };
    bool fits = true;
    for (int i = 0; i < count && fits; ++i) {
      const float lo = units(childLo[i] - nodeLo), hi = units(childHi[i] - nodeLo);
      int qLo = int(lo);
      int qHi = int(hi);
      qHi += float(qHi) < hi;  // ceil
      while (qLo > 0 && decode(nodeLo, scale, std::uint8_t(qLo)) > childLo[i]) --qLo;
      while (qHi < 255 && decode(nodeLo, scale, std::uint8_t(qHi)) < childHi[i]) ++qHi;
      fits = decode(nodeLo, scale, std::uint8_t(qLo)) <= childLo[i] &&
             decode(nodeLo, scale, std::uint8_t(qHi)) >= childHi[i];
      w.lo[axis][i] = std::uint8_t(qLo);
      w.hi[axis][i] = std::uint8_t(qHi);
    }
    if (fits || scale >= std::ldexp(1.0f, 127)) break;
    scale *= 2.0f;
  }
  w.origin[axis] = nodeLo;
  w.scale[axis] = scale;
  for (int i = count; i < kWidth; ++i) w.lo[axis][i] = 255, w.hi[axis][i] = 0;
}

// One axis of up to kWidth child boxes; empty slots repeat the first child's planes, finite
// values that the kernels mask out.
void setPlanes(WideNode& w, int axis, const float* childLo, const float* childHi, int count) noexcept {
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

template <class Node>
struct Collapse {
  const Bvh& binary;
  std::vector<Subtree> merged;  // per binary node
  std::vector<Node, HugePageAllocator<Node>>& out;

  bool isLeaf(std::uint32_t node) const noexcept { return merged[node].count != 0; }
};

template <class Node>
std::uint32_t collapse(const Collapse<Node>& c, std::uint32_t binaryNode) {
  const Bvh& binary = c.binary;
  auto& out = c.out;
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
    Node& w = out[index];
    for (int axis = 0; axis < 3; ++axis) {
      float lo[kWidth] = {}, hi[kWidth] = {};
      for (int i = 0; i < count; ++i) lo[i] = binary.nodes[slots[i]].min[axis], hi[i] = binary.nodes[slots[i]].max[axis];
      setPlanes(w, axis, lo, hi, count);
    }
    for (int i = 0; i < kWidth; ++i) {
      w.child[i] = 0;
      w.count[i] = Node::kEmpty;
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

Aabb QuantizedWideNode::childBox(int i) const noexcept {
  Aabb box;
  for (int a = 0; a < 3; ++a) {
    box.min[a] = decode(origin[a], scale[a], lo[a][i]);
    box.max[a] = decode(origin[a], scale[a], hi[a][i]);
  }
  return box;
}

template <class Node>
std::vector<Node, HugePageAllocator<Node>> collapseToWide(const Bvh& binary, std::uint32_t mergeLeafSize) {
  std::vector<Node, HugePageAllocator<Node>> out;
  if (binary.empty()) return out;
  Collapse<Node> c{binary, std::vector<Subtree>(binary.nodes.size()), out};
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

template WideNodes collapseToWide<WideNode>(const Bvh&, std::uint32_t);
template QuantizedWideNodes collapseToWide<QuantizedWideNode>(const Bvh&, std::uint32_t);

}  // namespace vt::collision
