#pragma once
// The BVH query kernels, one set per instruction set (kernel_set.inc compiled by each
// kernels_*.cpp), and the set chosen at run time (simd.cpp).
#include <glm/glm.hpp>

#include "vt/collision/mesh_bvh.hpp"

namespace vt::collision {

/// The walks over one node format: a MeshBvh's nodes and leaf-ordered triangle packs.
template <class Node>
struct WalkKernels {
  /// One ray: the nearest hit with t in (tMin, tMax) into `best`, or false.
  bool (*intersect)(const Node* nodes, const TrianglePack* packs, const PreparedRay& ray, float tMin, float tMax,
                    MeshHit& best) noexcept;
  /// One point: the nearest surface point with squared distance < limit into `best`, or false.
  bool (*closestPoint)(const Node* nodes, const TrianglePack* packs, const glm::vec3& point, float limit,
                       MeshHit& best) noexcept;
  /// `count` (<= kMaxQueryBatch) rays at once; tMax[i] is ray i's limit on entry and its
  /// nearest hit distance on exit. Bit i set = ray i hit.
  std::uint32_t (*intersects)(const Node* nodes, const TrianglePack* packs, const PreparedRay* rays,
                              const float* tMin, float* tMax, MeshHit* best, int count) noexcept;
  /// `count` (<= kMaxQueryBatch) queries at once; limits[i] is query i's squared search
  /// radius on entry and its nearest squared distance on exit. Bit i set = query i found one.
  std::uint32_t (*closestPoints)(const Node* nodes, const TrianglePack* packs, const glm::vec3* points,
                                 float* limits, MeshHit* best, int count) noexcept;
};

/// One instruction set's kernels.
struct QueryKernels {
  WalkKernels<WideNode> floatNodes;
  WalkKernels<QuantizedWideNode> quantizedNodes;
  /// A node's slots in the order a walk pushes three or more hit children: the hits in `mask`
  /// farthest key first, then the misses. Only steers the walk (no answer shows a wrong order),
  /// so the tests compare it across the sets here.
  void (*orderChildren)(const float (&key)[kWidth], unsigned mask, std::uint8_t (&slots)[kWidth]) noexcept;
};

namespace sse2 {
extern const QueryKernels kKernels;
}
#if defined(__x86_64__)
namespace avx2 {
extern const QueryKernels kKernels;
}
namespace avx512 {
extern const QueryKernels kKernels;
}
namespace avx512_on_avx2 {
extern const QueryKernels kKernels;
}
#endif

/// The kernels of the current simdLevel(). Any thread.
const QueryKernels& activeKernels() noexcept;

}  // namespace vt::collision
