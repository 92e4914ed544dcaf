#include "vt/collision/bvh.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>

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

// A primitive as the builder moves it: box and centre side by side, sorted in place, so every
// pass over a range reads memory in order instead of gathering through indices.
struct PrimRef {
  V4 lo, hi, c;  // hi[3] holds the primitive index's bits

  std::uint32_t id() const noexcept { return std::bit_cast<std::uint32_t>(hi[3]); }
};

// A box and the box of the centres inside it.
struct Bounds {
  V4 lo = V4{} + kBig, hi = V4{} - kBig, cLo = V4{} + kBig, cHi = V4{} - kBig;

  void add(const PrimRef& p) noexcept {
    lo = vmin(lo, p.lo);
    hi = vmax(hi, p.hi);
    cLo = vmin(cLo, p.c);
    cHi = vmax(cHi, p.c);
  }
};

struct Range {
  std::uint32_t node, begin, end, depth;
  Bounds bounds;
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
Split findSplit(std::span<const PrimRef> prims, const Bounds& bounds, int binCount) {
  struct Bins {
    std::array<V4, kMaxBins> lo, hi;
    std::array<std::uint32_t, kMaxBins> count;
  };
  std::array<Bins, 3> bins;
  const auto used = std::size_t(binCount);
  for (Bins& b : bins) {
    std::fill_n(b.lo.begin(), used, V4{} + kBig);
    std::fill_n(b.hi.begin(), used, V4{} - kBig);
    std::fill_n(b.count.begin(), used, 0u);
  }
  const V4 extent = bounds.cHi - bounds.cLo;
  V4 scale;
  for (int a = 0; a < 4; ++a) scale[a] = a < 3 && extent[a] > 0.0f ? float(binCount) / extent[a] : 0.0f;
  const V4 last = V4{} + float(binCount - 1);
  for (const PrimRef& p : prims) {
    const V4i bin = __builtin_convertvector(vmin(vmax((p.c - bounds.cLo) * scale, V4{}), last), V4i);
    for (int a = 0; a < 3; ++a) {
      Bins& b = bins[std::size_t(a)];
      const auto i = std::size_t(bin[a]);
      b.lo[i] = vmin(b.lo[i], p.lo);
      b.hi[i] = vmax(b.hi[i], p.hi);
      ++b.count[i];
    }
  }
  Split best;
  best.cost = kBig;
  std::array<float, kMaxBins> rightCost;
  for (int a = 0; a < 3; ++a) {
    if (scale[a] == 0.0f) continue;  // flat along this axis: every centre is in bin 0
    const Bins& b = bins[std::size_t(a)];
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

// Moves the primitives left of the split to the front, gathering both sides' bounds on the
// way (the children's bounds then cost no extra pass). Returns the first right-hand index.
std::uint32_t partition(std::span<PrimRef> prims, const Split& split, const Bounds& bounds, int binCount,
                        Bounds& left, Bounds& right) noexcept {
  const int a = split.axis;
  const float lo = bounds.cLo[a], scale = float(binCount) / (bounds.cHi[a] - bounds.cLo[a]);
  auto isLeft = [&](const PrimRef& p) { return binIndex(p.c[a], lo, scale, binCount) < split.bin; };
  std::size_t i = 0, j = prims.size();
  for (;;) {
    while (i < j && isLeft(prims[i])) left.add(prims[i++]);
    while (i < j && !isLeft(prims[j - 1])) right.add(prims[--j]);
    if (i >= j) break;
    std::swap(prims[i], prims[j - 1]);
    left.add(prims[i++]);
    right.add(prims[--j]);
  }
  return std::uint32_t(i);
}

Bounds boundsOf(std::span<const PrimRef> prims) noexcept {
  Bounds b;
  for (const PrimRef& p : prims) b.add(p);
  return b;
}

}  // namespace

Bvh buildBvh(std::span<const Aabb> boxes, std::span<const glm::vec3> centers, const BuildConfig& config) {
  if (boxes.size() != centers.size()) fail("bvh: ", boxes.size(), " boxes but ", centers.size(), " centres");
  if (boxes.size() >= 0x7fffffffu) fail("bvh: too many primitives (", boxes.size(), ")");
  const int binCount = std::clamp(config.binCount, 2, kMaxBins);
  const auto maxLeaf = std::uint32_t(std::max(config.maxLeafSize, 1));
  Bvh bvh;
  if (boxes.empty()) return bvh;
  std::vector<PrimRef> refs(boxes.size());
  Bounds rootBounds;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    refs[i] = {load(boxes[i].min), load(boxes[i].max), load(centers[i])};
    refs[i].hi[3] = std::bit_cast<float>(std::uint32_t(i));
    rootBounds.add(refs[i]);
  }
  // At most 2n - 1 nodes; only the pages actually used are ever touched, so no shrink (a copy).
  bvh.nodes.reserve(2 * boxes.size());
  bvh.nodes.push_back({});
  std::vector<Range> stack{{0, 0, std::uint32_t(boxes.size()), 0, rootBounds}};
  while (!stack.empty()) {
    const Range r = stack.back();
    stack.pop_back();
    const std::uint32_t count = r.end - r.begin;
    bvh.nodes[r.node] = {store(r.bounds.lo), r.begin, store(r.bounds.hi), count};
    if (count == 1) continue;
    const std::span<PrimRef> prims(refs.data() + r.begin, count);
    const Split split = r.depth < kMaxSahDepth ? findSplit(prims, r.bounds, binCount) : Split{};
    std::uint32_t mid = r.begin;
    Bounds left, right;
    if (split.axis >= 0) {
      // SAH: traversal + children's expected tests vs testing every primitive here.
      const float splitCost =
          config.traversalCost + split.cost / std::max(halfArea(r.bounds.lo, r.bounds.hi), 1e-30f);
      if (splitCost >= float(count) && count <= maxLeaf) continue;
      mid = r.begin + partition(prims, split, r.bounds, binCount, left, right);
    } else if (count <= maxLeaf) {
      continue;  // all centres coincide (or the tree is deep): nothing to gain from splitting
    }
    if (mid == r.begin || mid == r.end) {
      mid = r.begin + count / 2;
      left = boundsOf(prims.first(count / 2));
      right = boundsOf(prims.subspan(count / 2));
    }
    const auto child = std::uint32_t(bvh.nodes.size());
    bvh.nodes[r.node].index = child;
    bvh.nodes[r.node].count = 0;
    bvh.nodes.push_back({});
    bvh.nodes.push_back({});
    stack.push_back({child + 1, mid, r.end, r.depth + 1, right});
    stack.push_back({child, r.begin, mid, r.depth + 1, left});
  }
  bvh.primIds.resize(refs.size());
  for (std::size_t i = 0; i < refs.size(); ++i) bvh.primIds[i] = refs[i].id();
  return bvh;
}

}  // namespace vt::collision
