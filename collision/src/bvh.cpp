#include "vt/collision/bvh.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>

#include "vt/collision/huge_page_allocator.hpp"
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

// A primitive as the builder moves it: its box, sorted in place, so every pass over a range
// reads memory in order instead of gathering through indices. 32 bytes: the centre is not
// stored but taken as lo + hi (twice the centre; only its order matters). Lane 3 of lo and hi
// holds 23 bits each of the primitive index as the mantissa of a number in [1, 2), so the
// arithmetic that runs over lane 3 unused never meets a denormal, an infinity or a NaN.
struct PrimRef {
  V4 lo, hi;

  static PrimRef make(const Aabb& box, std::uint32_t id) noexcept {
    PrimRef p{load(box.min), load(box.max)};
    p.lo[3] = std::bit_cast<float>(kOne | (id & kMantissa));
    p.hi[3] = std::bit_cast<float>(kOne | id >> 23);
    return p;
  }
  V4 centre2() const noexcept { return lo + hi; }
  std::uint32_t id() const noexcept {
    return (std::bit_cast<std::uint32_t>(lo[3]) & kMantissa) | (std::bit_cast<std::uint32_t>(hi[3]) & kMantissa) << 23;
  }

  static constexpr std::uint32_t kOne = 0x3f800000u, kMantissa = 0x7fffffu;
};

// The box of a range. Bins span the box itself, not the tighter box of the centres: the box
// of each side comes out of the bins, so partitioning gathers nothing (binary-tree SAH cost on
// the 1M-triangle scene +0.03 %).
struct Box {
  V4 lo = V4{} + kBig, hi = V4{} - kBig;

  void add(const PrimRef& p) noexcept { lo = vmin(lo, p.lo), hi = vmax(hi, p.hi); }
  void add(const Box& b) noexcept { lo = vmin(lo, b.lo), hi = vmax(hi, b.hi); }
};

struct Split {
  int axis = -1;
  int bin = 0;         // primitives whose bin coordinate (see Bins) is < bin go left
  float lo = 0.0f;     // doubled-centre coordinate of bin 0's lower side along axis
  float scale = 0.0f;  // bins per unit of doubled-centre coordinate along axis
  float cost = 0.0f;
  float leftShare = 0.0f;  // of the primitives binned, the part left of the split
  Box left, right;
};

// Past this depth ranges are halved by count, so a tree never exceeds kMaxSahDepth + 31 levels
// and fixed traversal stacks (kTraversalStackSize = 64) cannot overflow.
constexpr std::uint32_t kMaxSahDepth = 32;

constexpr int kMaxBins = 64;

// Bins for a range of `count` primitives: fewer for small ranges, where the per-bin setup and
// sweep would cost more than the binning itself, up to the configured count from 24 on (with
// n / 8 instead of n / 2, queries on the 1M-triangle scene cost 1.5 % more instructions).
int binsFor(std::size_t count, int binCount) noexcept { return int(std::min(std::size_t(binCount), 4 + count / 2)); }

// Half areas of three boxes given by their extents (x, y, z in lanes 0-2), in lanes 0-2.
inline V4 halfAreas(V4 e0, V4 e1, V4 e2) noexcept {
  e0 = vmax(e0, V4{}), e1 = vmax(e1, V4{}), e2 = vmax(e2, V4{});
  const V4 xy = __builtin_shufflevector(e0, e1, 0, 4, 1, 5), z = __builtin_shufflevector(e0, e1, 2, 6, 2, 6);
  const V4 x = __builtin_shufflevector(xy, e2, 0, 1, 4, 4), y = __builtin_shufflevector(xy, e2, 2, 3, 5, 5);
  const V4 zz = __builtin_shufflevector(z, e2, 0, 1, 6, 6);
  return x * y + y * zz + zz * x;
}

// One range's bins on all three axes at once, by doubled centre over the range's box.
struct Bins {
  struct alignas(128) Bin {  // a power-of-two size: a bin index becomes an address in one shift
    std::array<V4, 3> lo, hi;  // [axis]
    V4i count;                 // lane a: primitives in this bin along axis a
  };
  std::array<Bin, kMaxBins> bin;
  V4 cLo, scale, last;
  int used;
  bool sampled;  // only some of the range's primitives were added: the bins' boxes fall short

  void reset(const Box& box, int binCount, std::uint32_t sampleMask) noexcept {
    used = binCount;
    sampled = sampleMask != 0;
    cLo = box.lo + box.lo;
    const V4 extent = box.hi + box.hi - cLo;
    // An extent too small for a finite scale counts as flat (partition's test relies on it).
    for (int a = 0; a < 4; ++a) scale[a] = a < 3 && extent[a] * kBig > float(binCount) ? float(binCount) / extent[a] : 0.0f;
    last = V4{} + float(binCount - 1);
    for (int k = 0; k < binCount; ++k) {
      Bin& b = bin[std::size_t(k)];
      b.lo.fill(V4{} + kBig);
      b.hi.fill(V4{} - kBig);
      b.count = V4i{};
    }
  }
  void add(const PrimRef& p) noexcept {
    // Clamped below too: a sampled range's children bin in the box of the parent's samples,
    // which some of their primitives lie outside of (partition's test agrees: below bin 0 is
    // left of every split, above the last bin right of it).
    const V4i index = __builtin_convertvector(vmax(vmin((p.centre2() - cLo) * scale, last), V4{}), V4i);
    for (int a = 0; a < 3; ++a) {
      Bin& b = bin[std::uint32_t(index[a])];
      b.lo[std::size_t(a)] = vmin(b.lo[std::size_t(a)], p.lo);
      b.hi[std::size_t(a)] = vmax(b.hi[std::size_t(a)], p.hi);
      ++b.count[a];
    }
  }
  void merge(const Bins& other) noexcept {
    for (int k = 0; k < used; ++k) {
      Bin& b = bin[std::size_t(k)];
      const Bin& o = other.bin[std::size_t(k)];
      for (std::size_t a = 0; a < 3; ++a) b.lo[a] = vmin(b.lo[a], o.lo[a]), b.hi[a] = vmax(b.hi[a], o.hi[a]);
      b.count += o.count;
    }
  }

  // Best SAH split of the binned primitives: one sweep each way that scores the three axes
  // together (lane a = axis a).
  Split best() const noexcept {
    // Right-hand costs of splitting before bin k, then left-hand sweep adding them up. A lane
    // whose left side is empty or everything (also every lane of a flat axis) never wins.
    std::array<V4, kMaxBins> rightCost;
    std::array<V4, 3> lo, hi;
    std::int32_t total = 0;  // primitives binned (a sample of a large range)
    for (int k = 0; k < used; ++k) total += bin[std::size_t(k)].count[0];
    lo.fill(V4{} + kBig), hi.fill(V4{} - kBig);
    V4i count{};
    for (int k = used - 1; k > 0; --k) {
      const Bin& b = bin[std::size_t(k)];
      for (std::size_t a = 0; a < 3; ++a) lo[a] = vmin(lo[a], b.lo[a]), hi[a] = vmax(hi[a], b.hi[a]);
      count += b.count;
      rightCost[std::size_t(k)] = halfAreas(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) * __builtin_convertvector(count, V4);
    }
    lo.fill(V4{} + kBig), hi.fill(V4{} - kBig);
    count = V4i{};
    V4 bestCost = V4{} + kBig;
    V4i bestBin{}, bestCount{};
    for (int k = 1; k < used; ++k) {
      const Bin& b = bin[std::size_t(k - 1)];
      for (std::size_t a = 0; a < 3; ++a) lo[a] = vmin(lo[a], b.lo[a]), hi[a] = vmax(hi[a], b.hi[a]);
      count += b.count;
      V4 cost = halfAreas(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) * __builtin_convertvector(count, V4) +
                rightCost[std::size_t(k)];
      cost = ((count == 0) | (count == total)) ? V4{} + kBig : cost;
      const V4i better = cost < bestCost;
      bestCost = better ? cost : bestCost;
      bestBin = better ? V4i{} + k : bestBin;
      bestCount = better ? count : bestCount;
    }
    Split split;
    split.cost = kBig;
    for (int a = 0; a < 3; ++a) {
      if (bestCost[a] < split.cost) split.axis = a, split.bin = bestBin[a], split.cost = bestCost[a];
    }
    if (split.axis < 0) return split;
    const auto a = std::size_t(split.axis);
    split.lo = cLo[split.axis];
    split.scale = scale[split.axis];
    split.leftShare = float(bestCount[split.axis]) / float(total);
    for (int k = 0; k < used; ++k) {
      const Bin& b = bin[std::size_t(k)];
      (k < split.bin ? split.left : split.right).add(Box{b.lo[a], b.hi[a]});
    }
    return split;
  }
};

// Bins a range in one pass: two sets, even and odd primitives, since neighbours often share a
// bin and one set would make each update wait for the previous one's store. Small ranges (most
// of them) use one set: there, resetting and merging the second costs more than the waits.
constexpr std::size_t kTwoSetsFrom = 64;

// Ranges larger than this bin one primitive in kSampleStride: hundreds of samples and more
// place a split among the bins about as well as all of them would, for a quarter of the
// binning of the top ten levels of a 1M-triangle tree. Measured there (scripts/collision-ab.sh,
// docs/PERFORMANCE.md): builds 1.12x faster, rays and spheres unchanged; sampling from 256
// made rays 4 % slower, one in eight from 16k on 3 %.
constexpr std::size_t kSampledFrom = 1024;
constexpr std::uint32_t kSampleStride = 4;
std::uint32_t sampleMask(std::size_t count) noexcept { return count > kSampledFrom ? kSampleStride - 1 : 0; }

void binRange(std::span<const PrimRef> prims, const Box& box, int binCount, Bins& bins, Bins& odd) noexcept {
  const std::uint32_t mask = sampleMask(prims.size());
  const std::size_t step = mask + 1;
  bins.reset(box, binCount, mask);
  if (prims.size() < kTwoSetsFrom) {
    for (const PrimRef& p : prims) bins.add(p);
    return;
  }
  odd.reset(box, binCount, mask);
  std::size_t i = 0;
  for (; i + step < prims.size(); i += 2 * step) bins.add(prims[i]), odd.add(prims[i + step]);
  if (i < prims.size()) bins.add(prims[i]);
  bins.merge(odd);
}

struct Range {
  std::uint32_t node, begin, end, depth;
  Box box;
  bool binned;  // its bins were filled while its parent was partitioned
};

// Moves the primitives left of the split to the front; returns the first right-hand index.
// The test repeats Bins::add's arithmetic exactly (the bin index truncates a value that is
// below bin exactly when the value is), so each side holds what its bins counted, and the
// split's boxes are each side's unless the bins were sampled: then each side's box is
// gathered into `sides` (left, right) when given. Each side's primitives are binned on the way into `left`
// / `right` when given (the children's own binning pass then reads nothing), one in every
// mask + 1.
std::uint32_t partition(std::span<PrimRef> prims, const Split& split, Bins* left, std::uint32_t leftMask, Bins* right,
                        std::uint32_t rightMask, Box* sides) noexcept {
  const int a = split.axis;
  const float bin = float(split.bin);
  std::uint32_t leftSeen = 0, rightSeen = 0;
  if (sides) sides[0] = sides[1] = Box{};
  auto isLeft = [&](const PrimRef& p) { return (p.lo[a] + p.hi[a] - split.lo) * split.scale < bin; };
  auto toLeft = [&](const PrimRef& p) {
    if (sides) sides[0].add(p);
    if (left && (leftSeen++ & leftMask) == 0) left->add(p);
  };
  auto toRight = [&](const PrimRef& p) {
    if (sides) sides[1].add(p);
    if (right && (rightSeen++ & rightMask) == 0) right->add(p);
  };
  std::size_t i = 0, j = prims.size();
  for (;;) {
    while (i < j && isLeft(prims[i])) toLeft(prims[i++]);
    while (i < j && !isLeft(prims[j - 1])) toRight(prims[--j]);
    if (i >= j) break;
    std::swap(prims[i], prims[j - 1]);
    toLeft(prims[i++]);
    toRight(prims[--j]);
  }
  return std::uint32_t(i);
}

float ownAreas(std::span<const PrimRef> prims) noexcept {
  float sum = 0.0f;
  for (const PrimRef& p : prims) sum += halfArea(p.lo, p.hi);
  return sum;
}

Box boxOf(std::span<const PrimRef> prims) noexcept {
  Box b;
  for (const PrimRef& p : prims) b.add(p);
  return b;
}

}  // namespace

Bvh buildBvh(std::span<const Aabb> boxes, const BuildConfig& config) {
  if (boxes.size() >= 0x7fffffffu) fail("bvh: too many primitives (", boxes.size(), ")");
  const int binCount = std::clamp(config.binCount, 2, kMaxBins);
  const auto maxLeaf = std::uint32_t(std::max(config.maxLeafSize, 1));
  const auto leafFloor = std::clamp(std::uint32_t(std::max(config.leafFloor, 1)), 1u, maxLeaf);
  Bvh bvh;
  if (boxes.empty()) return bvh;
  // Huge pages: the top levels stream the whole array several times. Written once, never zeroed.
  std::vector<PrimRef, HugePageAllocator<PrimRef>> refs;
  refs.reserve(boxes.size());
  Box rootBox;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    refs.push_back(PrimRef::make(boxes[i], std::uint32_t(i)));
    rootBox.add(refs.back());
  }
  // At most 2n - 1 nodes; only the pages actually used are ever touched, so no shrink (a copy).
  bvh.nodes.reserve(2 * boxes.size());
  bvh.nodes.push_back({});
  std::vector<Range> stack{{0, 0, std::uint32_t(boxes.size()), 0, rootBox, false}};
  // pending[s]: the bins of the range at stack position s, when binned; odd: binRange's second set.
  std::vector<Bins> pending(2);
  Bins odd;
  while (!stack.empty()) {
    const Range r = stack.back();
    stack.pop_back();
    const std::size_t slot = stack.size();
    if (pending.size() < slot + 2) pending.resize(slot + 2);  // this range's and its children's
    const std::uint32_t count = r.end - r.begin;
    bvh.nodes[r.node] = {store(r.box.lo), r.begin, store(r.box.hi), count};
    if (count <= leafFloor) continue;
    const std::span<PrimRef> prims(refs.data() + r.begin, count);
    const float area = std::max(halfArea(r.box.lo, r.box.hi), 1e-30f);
    // Any split costs at least the traversal step plus each primitive's own area (a child's
    // box holds it): ranges that can stay leaves and cannot beat that stay leaves unbinned.
    if (count <= maxLeaf && config.traversalCost + ownAreas(prims) / area >= float(count)) continue;
    Split split;
    bool exactBoxes = true;  // the split's boxes are its sides' (the right side's bins reuse this slot)
    if (r.depth < kMaxSahDepth) {
      if (!r.binned) binRange(prims, r.box, binsFor(count, binCount), pending[slot], odd);
      split = pending[slot].best();
      exactBoxes = !pending[slot].sampled;
    }
    std::uint32_t mid = r.begin;
    Box sides[2] = {split.left, split.right};
    Box &left = sides[0], &right = sides[1];
    bool binLeft = false, binRight = false;
    if (split.axis >= 0) {
      // SAH: traversal + children's expected tests vs testing every primitive here.
      const float splitCost = config.traversalCost + split.cost / area;
      if (splitCost >= float(count) && count <= maxLeaf) continue;
      // Children that will surely be binned (too big for a leaf) are binned while partitioning.
      // The right child stays at this stack position, the left one goes above it.
      // The children's sizes, estimated from the bins (exact unless this range was sampled).
      const auto leftCount = std::uint32_t(split.leftShare * float(count) + 0.5f), rightCount = count - leftCount;
      binLeft = leftCount > maxLeaf && r.depth + 1 < kMaxSahDepth;
      binRight = rightCount > maxLeaf && r.depth + 1 < kMaxSahDepth;
      Bins* leftBins = binLeft ? &pending[slot + 1] : nullptr;
      Bins* rightBins = binRight ? &pending[slot] : nullptr;
      // The children bin over the boxes the bins give (of the samples, if sampled).
      if (leftBins) leftBins->reset(split.left, binsFor(leftCount, binCount), sampleMask(leftCount));
      if (rightBins) rightBins->reset(split.right, binsFor(rightCount, binCount), sampleMask(rightCount));
      mid = r.begin + partition(prims, split, leftBins, sampleMask(leftCount), rightBins, sampleMask(rightCount),
                                exactBoxes ? nullptr : sides);
    } else if (count <= maxLeaf) {
      continue;  // all centres coincide (or the tree is deep): nothing to gain from splitting
    }
    if (mid == r.begin || mid == r.end) {
      mid = r.begin + count / 2;
      left = boxOf(prims.first(count / 2));
      right = boxOf(prims.subspan(count / 2));
      binLeft = binRight = false;
    }
    const auto child = std::uint32_t(bvh.nodes.size());
    bvh.nodes[r.node].index = child;
    bvh.nodes[r.node].count = 0;
    bvh.nodes.push_back({});
    bvh.nodes.push_back({});
    stack.push_back({child + 1, mid, r.end, r.depth + 1, right, binRight});
    stack.push_back({child, r.begin, mid, r.depth + 1, left, binLeft});
  }
  bvh.primIds.resize(refs.size());
  for (std::size_t i = 0; i < refs.size(); ++i) bvh.primIds[i] = refs[i].id();
  return bvh;
}

}  // namespace vt::collision
