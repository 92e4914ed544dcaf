#include "vt/collision/bvh.hpp"

#include <algorithm>
#include <array>
#include <numeric>

#include "vt/core/error.hpp"

namespace vt::collision {
namespace {

struct Bin {
  Aabb box = emptyBox();
  std::uint32_t count = 0;
};

struct Split {
  int axis = -1;
  int bin = 0;  // primitives with bin index < bin go left
  float cost = 0.0f;
};

struct Range {
  std::uint32_t node, begin, end, depth;
};

// Past this depth ranges are halved by count, so a tree never exceeds kMaxSahDepth + 31 levels
// and fixed traversal stacks (kTraversalStackSize = 64) cannot overflow.
constexpr std::uint32_t kMaxSahDepth = 32;

constexpr int kMaxBins = 64;

int binIndex(float c, float lo, float scale, int binCount) noexcept {
  return std::clamp(int((c - lo) * scale), 0, binCount - 1);
}

// Best SAH split of one range over all three axes (one pass fills all bins).
Split findSplit(std::span<const std::uint32_t> prims, std::span<const Aabb> boxes, std::span<const glm::vec3> centers,
                const Aabb& centerBox, int binCount) {
  std::array<std::array<Bin, kMaxBins>, 3> bins{};
  const glm::vec3 extent = centerBox.max - centerBox.min;
  glm::vec3 scale;
  for (int a = 0; a < 3; ++a) scale[a] = extent[a] > 0.0f ? float(binCount) / extent[a] : 0.0f;
  for (std::uint32_t p : prims) {
    for (int a = 0; a < 3; ++a) {
      if (scale[a] == 0.0f) continue;
      Bin& bin = bins[a][binIndex(centers[p][a], centerBox.min[a], scale[a], binCount)];
      bin.box = merge(bin.box, boxes[p]);
      ++bin.count;
    }
  }
  Split best;
  best.cost = 3.4e38f;
  for (int a = 0; a < 3; ++a) {
    if (scale[a] == 0.0f) continue;
    std::array<float, kMaxBins> rightCost{};
    Aabb box = emptyBox();
    std::uint32_t count = 0;
    for (int b = binCount - 1; b > 0; --b) {
      box = merge(box, bins[a][b].box);
      count += bins[a][b].count;
      rightCost[b] = count ? halfArea(box) * float(count) : 0.0f;
    }
    box = emptyBox();
    count = 0;
    for (int b = 1; b < binCount; ++b) {
      box = merge(box, bins[a][b - 1].box);
      count += bins[a][b - 1].count;
      if (count == 0 || count == prims.size()) continue;
      const float cost = halfArea(box) * float(count) + rightCost[b];
      if (cost < best.cost) best = {a, b, cost};
    }
  }
  return best;
}

}  // namespace

Bvh buildBvh(std::span<const Aabb> boxes, std::span<const glm::vec3> centers, const BuildConfig& config) {
  if (boxes.size() != centers.size()) fail("bvh: ", boxes.size(), " boxes but ", centers.size(), " centres");
  if (boxes.size() >= 0x7fffffffu) fail("bvh: too many primitives (", boxes.size(), ")");
  const int binCount = std::clamp(config.binCount, 2, kMaxBins);
  const auto maxLeaf = std::uint32_t(std::max(config.maxLeafSize, 1));
  Bvh bvh;
  if (boxes.empty()) return bvh;
  bvh.primIds.resize(boxes.size());
  std::iota(bvh.primIds.begin(), bvh.primIds.end(), 0u);
  bvh.nodes.reserve(2 * boxes.size());
  bvh.nodes.push_back({});
  std::vector<Range> stack{{0, 0, std::uint32_t(boxes.size()), 0}};
  while (!stack.empty()) {
    const Range r = stack.back();
    stack.pop_back();
    Aabb box = emptyBox(), centerBox = emptyBox();
    for (std::uint32_t i = r.begin; i < r.end; ++i) {
      const std::uint32_t p = bvh.primIds[i];
      box = merge(box, boxes[p]);
      centerBox = merge(centerBox, {centers[p], centers[p]});
    }
    const std::uint32_t count = r.end - r.begin;
    BvhNode& node = bvh.nodes[r.node];
    node = {box.min, r.begin, box.max, count};
    if (count == 1) continue;
    const std::span<std::uint32_t> prims(bvh.primIds.data() + r.begin, count);
    const Split split = r.depth < kMaxSahDepth ? findSplit(prims, boxes, centers, centerBox, binCount) : Split{};
    std::uint32_t mid = r.begin;
    if (split.axis >= 0) {
      // SAH: traversal + children's expected tests vs testing every primitive here.
      const float splitCost = config.traversalCost + split.cost / std::max(halfArea(box), 1e-30f);
      if (splitCost >= float(count) && count <= maxLeaf) continue;
      const int a = split.axis;
      const float lo = centerBox.min[a];
      const float scale = float(binCount) / (centerBox.max[a] - centerBox.min[a]);
      auto it = std::partition(prims.begin(), prims.end(), [&](std::uint32_t p) {
        return binIndex(centers[p][a], lo, scale, binCount) < split.bin;
      });
      mid = r.begin + std::uint32_t(it - prims.begin());
    } else if (count <= maxLeaf) {
      continue;  // all centres coincide (or the tree is deep): nothing to gain from splitting
    }
    if (mid == r.begin || mid == r.end) mid = r.begin + count / 2;
    const auto child = std::uint32_t(bvh.nodes.size());
    bvh.nodes[r.node].index = child;
    bvh.nodes[r.node].count = 0;
    bvh.nodes.push_back({});
    bvh.nodes.push_back({});
    stack.push_back({child + 1, mid, r.end, r.depth + 1});
    stack.push_back({child, r.begin, mid, r.depth + 1});
  }
  bvh.nodes.shrink_to_fit();
  return bvh;
}

void refitBvh(Bvh& bvh, std::span<const Aabb> boxes) noexcept {
  // Children always follow their parent, so a reverse sweep sees children first.
  for (std::size_t i = bvh.nodes.size(); i-- > 0;) {
    BvhNode& node = bvh.nodes[i];
    Aabb box = emptyBox();
    if (node.isLeaf()) {
      for (std::uint32_t k = 0; k < node.count; ++k) box = merge(box, boxes[bvh.primIds[node.index + k]]);
    } else {
      const BvhNode& a = bvh.nodes[node.index];
      const BvhNode& b = bvh.nodes[node.index + 1];
      box = {glm::min(a.min, b.min), glm::max(a.max, b.max)};
    }
    node.min = box.min;
    node.max = box.max;
  }
}

}  // namespace vt::collision
