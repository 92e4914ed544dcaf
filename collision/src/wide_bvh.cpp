#include "vt/collision/wide_bvh.hpp"

#include <algorithm>

namespace vt::collision {
namespace {

std::uint32_t collapse(const Bvh& binary, std::uint32_t binaryNode, std::vector<WideNode>& out) {
  // Open the largest inner children until the node is full (SAH: big boxes are hit most).
  std::uint32_t slots[kWidth] = {binaryNode};
  int count = 1;
  const BvhNode& root = binary.nodes[binaryNode];
  if (!root.isLeaf()) {
    slots[0] = root.index;
    slots[1] = root.index + 1;
    count = 2;
  }
  while (count < kWidth) {
    int best = -1;
    float bestArea = -1.0f;
    for (int i = 0; i < count; ++i) {
      const BvhNode& n = binary.nodes[slots[i]];
      const float area = halfArea({n.min, n.max});
      if (!n.isLeaf() && area > bestArea) best = i, bestArea = area;
    }
    if (best < 0) break;
    const std::uint32_t opened = slots[best];
    slots[best] = binary.nodes[opened].index;
    slots[count++] = binary.nodes[opened].index + 1;
  }
  const auto index = std::uint32_t(out.size());
  out.push_back({});
  for (int i = 0; i < kWidth; ++i) {
    WideNode& w = out[index];  // re-fetched: recursion below may reallocate `out`
    if (i >= count) {
      w.minX[i] = w.minY[i] = w.minZ[i] = 0.0f;
      w.maxX[i] = w.maxY[i] = w.maxZ[i] = 0.0f;
      w.child[i] = 0;
      w.count[i] = WideNode::kEmpty;
      continue;
    }
    const BvhNode& n = binary.nodes[slots[i]];
    w.minX[i] = n.min.x, w.minY[i] = n.min.y, w.minZ[i] = n.min.z;
    w.maxX[i] = n.max.x, w.maxY[i] = n.max.y, w.maxZ[i] = n.max.z;
    if (n.isLeaf()) {
      w.child[i] = n.index;
      w.count[i] = n.count;
    } else {
      const std::uint32_t child = collapse(binary, slots[i], out);
      out[index].child[i] = child;
      out[index].count[i] = 0;
    }
  }
  return index;
}

}  // namespace

std::vector<WideNode> collapseToWide(const Bvh& binary) {
  std::vector<WideNode> out;
  if (binary.empty()) return out;
  out.reserve(binary.nodes.size() / 2 + 1);
  collapse(binary, 0, out);
  out.shrink_to_fit();
  return out;
}

}  // namespace vt::collision
