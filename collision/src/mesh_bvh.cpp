#include "vt/collision/mesh_bvh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "vt/core/error.hpp"

namespace vt::collision {

MeshBvh::MeshBvh(const Mesh& mesh, const std::string& name, const BuildConfig& config, const glm::mat3& linear) {
  if (mesh.indices.size() % 3 != 0) {
    fail("collision: mesh '", name, "': index count ", mesh.indices.size(), " is not a multiple of 3");
  }
  std::vector<TrianglePositions> tris;
  std::vector<std::uint32_t> ids;
  tris.reserve(mesh.triangleCount());
  ids.reserve(mesh.triangleCount());
  for (std::size_t i = 0; i < mesh.triangleCount(); ++i) {
    glm::vec3 p[3], q[3];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t index = mesh.indices[3 * i + std::size_t(k)];
      if (index >= mesh.vertices.size()) {
        fail("collision: mesh '", name, "': triangle ", i, " uses vertex ", index, " of ", mesh.vertices.size());
      }
      q[k] = mesh.vertices[index].position;
      p[k] = linear * q[k];
    }
    // Judged in the mesh's own frame so a baked instance keeps exactly the same triangles.
    if (isDegenerate(q[0], q[1], q[2]) || isDegenerate(p[0], p[1], p[2])) continue;
    tris.push_back({p[0], p[1], p[2]});
    ids.push_back(std::uint32_t(i));
  }
  std::vector<Aabb> boxes(tris.size());
  std::vector<glm::vec3> centers(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i) {
    const TrianglePositions& t = tris[i];
    boxes[i] = {glm::min(t.p0, glm::min(t.p1, t.p2)), glm::max(t.p0, glm::max(t.p1, t.p2))};
    centers[i] = (boxes[i].min + boxes[i].max) * 0.5f;
  }
  const Bvh bvh = buildBvh(boxes, centers, config);
  m_triangles.resize(tris.size());
  m_meshTriangle.resize(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i) {
    m_triangles[i] = tris[bvh.primIds[i]];
    m_meshTriangle[i] = ids[bvh.primIds[i]];
  }
  // Leaves index m_triangles directly (already in primIds order).
  const std::vector<WideNode> wide = collapseToWide(bvh);
  m_nodes.assign(wide.begin(), wide.end());
  if (!bvh.empty()) m_bounds = {bvh.nodes[0].min, bvh.nodes[0].max};
}

Aabb MeshBvh::bounds() const noexcept { return m_bounds; }

namespace {

struct Entry {
  std::uint32_t child;
  std::uint32_t count;  // 0 = wide node, else leaf size
  float key;            // ray entry distance or squared point distance
};

// Pushes a node's hit children farthest first, so the nearest is popped next. Usually one
// or two children qualify: those cases avoid the general sort (branch mispredictions).
inline void pushSortedImpl(const WideNode& n, const float (&key)[kWidth], float limit, Entry* stack,
                           int& top) noexcept {
  unsigned mask = 0;
  for (int i = 0; i < kWidth; ++i) mask |= unsigned(key[i] < limit) << i;
  if (mask == 0) return;
  if (top + kWidth > kWideStackSize) return;  // cannot happen for builder trees (depth-limited)
  const int first = __builtin_ctz(mask);
  mask &= mask - 1;
  if (mask == 0) {
    stack[top++] = {n.child[first], n.count[first], key[first]};
    return;
  }
  const int second = __builtin_ctz(mask);
  mask &= mask - 1;
  if (mask == 0) {
    const bool firstNear = key[first] <= key[second];
    const int a = firstNear ? second : first, b = firstNear ? first : second;
    stack[top++] = {n.child[a], n.count[a], key[a]};
    stack[top++] = {n.child[b], n.count[b], key[b]};
    return;
  }
  Entry hits[kWidth] = {{n.child[first], n.count[first], key[first]}, {n.child[second], n.count[second], key[second]}};
  int count = 2;
  for (; mask; mask &= mask - 1) {
    const int i = __builtin_ctz(mask);
    hits[count++] = {n.child[i], n.count[i], key[i]};
  }
  for (int i = 1; i < count; ++i) {  // insertion sort, descending
    const Entry e = hits[i];
    int j = i;
    for (; j > 0 && hits[j - 1].key < e.key; --j) hits[j] = hits[j - 1];
    hits[j] = e;
  }
  for (int i = 0; i < count; ++i) stack[top++] = hits[i];
}

// Starts loading what the pushed entries point at: on large meshes queries wait on memory,
// and a node's children are independent loads that can overlap.
inline void pushSorted(const WideNode& n, const float (&key)[kWidth], float limit, Entry* stack, int& top,
                       const WideNode* nodes, const TrianglePositions* triangles) noexcept {
  const int before = top;
  pushSortedImpl(n, key, limit, stack, top);
  for (int i = before; i < top; ++i) {
    if (stack[i].count == 0) {
      const char* p = reinterpret_cast<const char*>(nodes + stack[i].child);
      for (std::size_t line = 0; line < sizeof(WideNode); line += 64) __builtin_prefetch(p + line);
    } else {
      const char* p = reinterpret_cast<const char*>(triangles + stack[i].child);
      const std::size_t bytes = std::min<std::size_t>(stack[i].count * sizeof(TrianglePositions), 256);
      for (std::size_t line = 0; line < bytes; line += 64) __builtin_prefetch(p + line);
    }
  }
}

#if defined(__SSE2__)
// Four boxes per SSE instruction (x86-64 always has SSE2; other targets use the loop below).
struct RayLanes {
  __m128 ox, oy, oz, ix, iy, iz;
  explicit RayLanes(const PreparedRay& ray) noexcept
      : ox(_mm_set1_ps(ray.origin.x)), oy(_mm_set1_ps(ray.origin.y)), oz(_mm_set1_ps(ray.origin.z)),
        ix(_mm_set1_ps(ray.invDirection.x)), iy(_mm_set1_ps(ray.invDirection.y)), iz(_mm_set1_ps(ray.invDirection.z)) {}
};

__m128 emptyLanes(const WideNode& n, int o) noexcept {
  return _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_load_si128(reinterpret_cast<const __m128i*>(n.count + o)),
                                          _mm_set1_epi32(-1)));
}

void rayBoxes(const WideNode& n, const RayLanes& r, float tMin, float tMax, float (&key)[kWidth]) noexcept {
  for (int o = 0; o < kWidth; o += 4) {
    const __m128 x0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.minX + o), r.ox), r.ix);
    const __m128 x1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.maxX + o), r.ox), r.ix);
    const __m128 y0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.minY + o), r.oy), r.iy);
    const __m128 y1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.maxY + o), r.oy), r.iy);
    const __m128 z0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.minZ + o), r.oz), r.iz);
    const __m128 z1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.maxZ + o), r.oz), r.iz);
    const __m128 nearT = _mm_max_ps(_mm_max_ps(_mm_min_ps(x0, x1), _mm_min_ps(y0, y1)),
                                    _mm_max_ps(_mm_min_ps(z0, z1), _mm_set1_ps(tMin)));
    // 1 + 2*gamma(3) (Ize 2013): robust slabs, so watertight hits are never culled.
    const __m128 farT = _mm_mul_ps(_mm_min_ps(_mm_min_ps(_mm_max_ps(x0, x1), _mm_max_ps(y0, y1)),
                                              _mm_min_ps(_mm_max_ps(z0, z1), _mm_set1_ps(tMax))),
                                   _mm_set1_ps(1.00000024f));
    const __m128 miss = _mm_or_ps(_mm_cmpgt_ps(nearT, farT), emptyLanes(n, o));
    const __m128 inf = _mm_set1_ps(std::numeric_limits<float>::infinity());
    _mm_storeu_ps(key + o, _mm_or_ps(_mm_and_ps(miss, inf), _mm_andnot_ps(miss, nearT)));
  }
}

void pointBoxes(const WideNode& n, const glm::vec3& p, float (&key)[kWidth]) noexcept {
  const __m128 px = _mm_set1_ps(p.x), py = _mm_set1_ps(p.y), pz = _mm_set1_ps(p.z), zero = _mm_setzero_ps();
  const __m128 inf = _mm_set1_ps(std::numeric_limits<float>::infinity());
  for (int o = 0; o < kWidth; o += 4) {
    const __m128 dx =
        _mm_max_ps(_mm_max_ps(_mm_sub_ps(_mm_load_ps(n.minX + o), px), _mm_sub_ps(px, _mm_load_ps(n.maxX + o))), zero);
    const __m128 dy =
        _mm_max_ps(_mm_max_ps(_mm_sub_ps(_mm_load_ps(n.minY + o), py), _mm_sub_ps(py, _mm_load_ps(n.maxY + o))), zero);
    const __m128 dz =
        _mm_max_ps(_mm_max_ps(_mm_sub_ps(_mm_load_ps(n.minZ + o), pz), _mm_sub_ps(pz, _mm_load_ps(n.maxZ + o))), zero);
    const __m128 d2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
    const __m128 empty = emptyLanes(n, o);
    _mm_storeu_ps(key + o, _mm_or_ps(_mm_and_ps(empty, inf), _mm_andnot_ps(empty, d2)));
  }
}
#else
struct RayLanes {
  glm::vec3 o, inv;
  explicit RayLanes(const PreparedRay& ray) noexcept : o(ray.origin), inv(ray.invDirection) {}
};

void rayBoxes(const WideNode& n, const RayLanes& r, float tMin, float tMax, float (&key)[kWidth]) noexcept {
  for (int i = 0; i < kWidth; ++i) {
    const float x0 = (n.minX[i] - r.o.x) * r.inv.x, x1 = (n.maxX[i] - r.o.x) * r.inv.x;
    const float y0 = (n.minY[i] - r.o.y) * r.inv.y, y1 = (n.maxY[i] - r.o.y) * r.inv.y;
    const float z0 = (n.minZ[i] - r.o.z) * r.inv.z, z1 = (n.maxZ[i] - r.o.z) * r.inv.z;
    const float nearT = std::max(std::max(std::min(x0, x1), std::min(y0, y1)), std::max(std::min(z0, z1), tMin));
    const float farT =
        std::min(std::min(std::max(x0, x1), std::max(y0, y1)), std::min(std::max(z0, z1), tMax)) * 1.00000024f;
    key[i] = nearT <= farT && n.count[i] != WideNode::kEmpty ? nearT : std::numeric_limits<float>::infinity();
  }
}

void pointBoxes(const WideNode& n, const glm::vec3& p, float (&key)[kWidth]) noexcept {
  for (int i = 0; i < kWidth; ++i) {
    const float dx = std::max(std::max(n.minX[i] - p.x, p.x - n.maxX[i]), 0.0f);
    const float dy = std::max(std::max(n.minY[i] - p.y, p.y - n.maxY[i]), 0.0f);
    const float dz = std::max(std::max(n.minZ[i] - p.z, p.z - n.maxZ[i]), 0.0f);
    const float d2 = dx * dx + dy * dy + dz * dz;
    key[i] = n.count[i] != WideNode::kEmpty ? d2 : std::numeric_limits<float>::infinity();
  }
}
#endif

}  // namespace

bool MeshBvh::intersect(const PreparedRay& ray, float tMin, MeshHit& best, float tMax) const noexcept {
  if (m_nodes.empty()) return false;
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const RayLanes r(ray);
  Entry stack[kWideStackSize];
  int top = 0;
  stack[top++] = {0, 0, tMin};
  bool found = false;
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.key > tMax) continue;  // a closer hit was found since this was pushed
    if (e.count != 0) {
      for (std::uint32_t i = e.child, end = e.child + e.count; i < end; ++i) {
        const TrianglePositions& tri = m_triangles[i];
        float t, u, v;
        if (intersectTriangle(ray, tri.p0, tri.p1, tri.p2, tMin, tMax, t, u, v)) {
          tMax = t;
          best.t = t;
          best.u = u;
          best.v = v;
          best.slot = i;
          found = true;
        }
      }
      continue;
    }
    const WideNode& n = m_nodes[e.child];
    float key[kWidth];
    rayBoxes(n, r, tMin, tMax, key);
    pushSorted(n, key, kInf, stack, top, m_nodes.data(), m_triangles.data());
  }
  if (found) best.triangle = m_meshTriangle[best.slot];
  return found;
}

bool MeshBvh::closestPoint(const glm::vec3& p, float maxDistanceSquared, MeshHit& best) const noexcept {
  if (m_nodes.empty()) return false;
  float bestD2 = maxDistanceSquared;
  Entry stack[kWideStackSize];
  int top = 0;
  stack[top++] = {0, 0, 0.0f};
  bool found = false;
  while (top > 0) {
    const Entry e = stack[--top];
    if (!(e.key < bestD2)) continue;  // ruled out by a closer point found since
    if (e.count != 0) {
      for (std::uint32_t i = e.child, end = e.child + e.count; i < end; ++i) {
        const TrianglePositions& tri = m_triangles[i];
        float u, v;
        const glm::vec3 q = closestPointOnTriangle(p, tri.p0, tri.p1, tri.p2, u, v);
        const glm::vec3 d = q - p;
        const float d2 = glm::dot(d, d);
        if (d2 < bestD2) {
          bestD2 = d2;
          best = {kNoHit, i, d2, u, v, q};
          found = true;
        }
      }
      continue;
    }
    const WideNode& n = m_nodes[e.child];
    float key[kWidth];
    pointBoxes(n, p, key);
    pushSorted(n, key, bestD2, stack, top, m_nodes.data(), m_triangles.data());
  }
  if (found) best.triangle = m_meshTriangle[best.slot];
  return found;
}

}  // namespace vt::collision
