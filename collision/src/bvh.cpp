#include "vt/collision/bvh.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>

#include "vt/core/error.hpp"

namespace vt::collision {
namespace {

// Four-lane vectors (GCC/Clang vector extensions: SSE2 on x86-64, NEON elsewhere). A box
// merge is two instructions instead of six scalar min/max, which is most of the binning.
using V4 = float __attribute__((vector_size(16)));
using V4i = std::int32_t __attribute__((vector_size(16)));

inline V4 vmin(V4 a, V4 b) noexcept { return a < b ? a : b; }
inline V4 vmax(V4 a, V4 b) noexcept { return a > b ? a : b; }
inline V4 load(const glm::vec3& v) noexcept { return V4{v.x, v.y, v.z, 0.0f}; }
inline glm::vec3 store(V4 v) noexcept { return {v[0], v[1], v[2]}; }
inline float halfArea(V4 lo, V4 hi) noexcept {
  const V4 e = vmax(hi - lo, V4{});
  return e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
}
constexpr float kBig = 3.4e38f;

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

// Best SAH split of one range over all three axes: one pass bins every primitive on all
// axes at once (the same arithmetic as binIndex, lane-wise), then one sweep per axis.
Split findSplit(std::span<const std::uint32_t> prims, std::span<const Aabb> boxes, std::span<const glm::vec3> centers,
                V4 centerMin, V4 centerMax, int binCount) {
  struct Bins {
    std::array<V4, kMaxBins> lo, hi;
    std::array<std::uint32_t, kMaxBins> count;
  };
  std::array<Bins, 3> bins;
  for (Bins& b : bins) {
    b.lo.fill(V4{} + kBig);
    b.hi.fill(V4{} - kBig);
    b.count.fill(0);
  }
  const V4 extent = centerMax - centerMin;
  V4 scale;
  for (int a = 0; a < 4; ++a) scale[a] = a < 3 && extent[a] > 0.0f ? float(binCount) / extent[a] : 0.0f;
  const V4 last = V4{} + float(binCount - 1);
  for (std::uint32_t p : prims) {
    const V4 lo = load(boxes[p].min), hi = load(boxes[p].max);
    const V4i bin = __builtin_convertvector(vmin(vmax((load(centers[p]) - centerMin) * scale, V4{}), last), V4i);
    for (int a = 0; a < 3; ++a) {
      Bins& b = bins[std::size_t(a)];
      const auto i = std::size_t(bin[a]);
      b.lo[i] = vmin(b.lo[i], lo);
      b.hi[i] = vmax(b.hi[i], hi);
      ++b.count[i];
    }
  }
  Split best;
  best.cost = kBig;
  for (int a = 0; a < 3; ++a) {
    if (scale[a] == 0.0f) continue;  // flat along this axis: every centre is in bin 0
    const Bins& b = bins[std::size_t(a)];
    std::array<float, kMaxBins> rightCost{};
    V4 lo = V4{} + kBig, hi = V4{} - kBig;
    std::uint32_t count = 0;
    for (int k = binCount - 1; k > 0; --k) {
      lo = vmin(lo, b.lo[std::size_t(k)]);
      hi = vmax(hi, b.hi[std::size_t(k)]);
      count += b.count[std::size_t(k)];
      rightCost[std::size_t(k)] = count ? halfArea(lo, hi) * float(count) : 0.0f;
    }
    lo = V4{} + kBig, hi = V4{} - kBig;
    count = 0;
    for (int k = 1; k < binCount; ++k) {
      lo = vmin(lo, b.lo[std::size_t(k - 1)]);
      hi = vmax(hi, b.hi[std::size_t(k - 1)]);
      count += b.count[std::size_t(k - 1)];
      if (count == 0 || count == prims.size()) continue;
      const float cost = halfArea(lo, hi) * float(count) + rightCost[std::size_t(k)];
      if (cost < best.cost) best = {a, k, cost};
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
  // At most 2n - 1 nodes; only the pages actually used are ever touched, so no shrink (a copy).
  bvh.nodes.reserve(2 * boxes.size());
  bvh.nodes.push_back({});
  std::vector<Range> stack{{0, 0, std::uint32_t(boxes.size()), 0}};
  while (!stack.empty()) {
    const Range r = stack.back();
    stack.pop_back();
    V4 lo = V4{} + kBig, hi = V4{} - kBig, cLo = lo, cHi = hi;
    for (std::uint32_t i = r.begin; i < r.end; ++i) {
      const std::uint32_t p = bvh.primIds[i];
      const V4 c = load(centers[p]);
      lo = vmin(lo, load(boxes[p].min));
      hi = vmax(hi, load(boxes[p].max));
      cLo = vmin(cLo, c);
      cHi = vmax(cHi, c);
    }
    const std::uint32_t count = r.end - r.begin;
    bvh.nodes[r.node] = {store(lo), r.begin, store(hi), count};
    if (count == 1) continue;
    const std::span<std::uint32_t> prims(bvh.primIds.data() + r.begin, count);
    const Split split = r.depth < kMaxSahDepth ? findSplit(prims, boxes, centers, cLo, cHi, binCount) : Split{};
    std::uint32_t mid = r.begin;
    if (split.axis >= 0) {
      // SAH: traversal + children's expected tests vs testing every primitive here.
      const float splitCost = config.traversalCost + split.cost / std::max(halfArea(lo, hi), 1e-30f);
      if (splitCost >= float(count) && count <= maxLeaf) continue;
      const int a = split.axis;
      const float cMin = cLo[a];
      const float scale = float(binCount) / (cHi[a] - cLo[a]);
      auto it = std::partition(prims.begin(), prims.end(), [&](std::uint32_t p) {
        return binIndex(centers[p][a], cMin, scale, binCount) < split.bin;
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
