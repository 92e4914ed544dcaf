#pragma once
// Triangle tests returning barycentrics (u = weight of p1, v = weight of p2, p0 gets 1-u-v),
// which is exactly what UV lookup needs. Pure, allocation-free, any thread.
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

// The hot tests are inline so BVH leaf loops can inline them.
namespace vt::collision {

/// 1 / direction with zero components replaced by a tiny value (no NaN in slab tests). Inline
/// and without branches (the zero test adds 1e-30 or an exact 0): every ray query starts here.
inline glm::vec3 safeInverse(const glm::vec3& d) noexcept {
  // Four lanes at once (glm's vec3 arithmetic goes one float at a time): d + 1e-30 where d is
  // zero, d + 0 elsewhere, then the reciprocal.
  using V4 = float __attribute__((vector_size(16)));
  using V4i = std::int32_t __attribute__((vector_size(16)));
  const V4 v{d.x, d.y, d.z, 1.0f};
  const V4 tiny = V4(V4i(v == V4{}) & V4i(V4{} + 1e-30f));
  const V4 inv = (V4{} + 1.0f) / (v + tiny);
  return {inv[0], inv[1], inv[2]};
}

/// A ray prepared for the watertight triangle test (Woop, Benthin, Wald 2013) and slab tests.
struct PreparedRay {
  glm::vec3 origin;
  glm::vec3 direction;
  glm::vec3 invDirection;  // zero components replaced by a tiny value: no NaN in slab tests
  // The shear that maps the ray onto +Z (Woop, Benthin, Wald 2013): kz is the axis of the
  // direction's largest component, and a vertex p relative to the origin maps to
  // (p[kx] - shearX p[kz], p[ky] - shearY p[kz], shearZ p[kz]).
  int kx, ky, kz;
  float shearX, shearY, shearZ;

  /// Unset (for arrays filled later).
  PreparedRay() noexcept = default;
  /// direction need not be normalised; hit distances are in units of |direction|.
  PreparedRay(const glm::vec3& origin, const glm::vec3& direction) noexcept;
};

inline PreparedRay::PreparedRay(const glm::vec3& o, const glm::vec3& d) noexcept
    : origin(o), direction(d), invDirection(safeInverse(d)) {
  // Without branches: rays come in every direction, so each branch here would be mispredicted
  // half the time, and the mispredictions cost more than the rest of the setup.
  const float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
  const int xy = ax > ay, xz = ax > az, yz = ay > az;
  kz = xy * (2 - 2 * xz) + (1 - xy) * (2 - yz);  // the axis of the largest component
  static constexpr int kNextAxis[3] = {1, 2, 0};  // a table: gcc turns arithmetic on kz into branches
  const int next = kNextAxis[kz], after = kNextAxis[next];
  // Arrays, not glm's operator[], which is a switch on the index.
  const float dv[3] = {d.x, d.y, d.z}, iv[3] = {invDirection.x, invDirection.y, invDirection.z};
  const int flip = dv[kz] < 0.0f;  // swapped: keeps the winding, so the edge tests stay consistent
  kx = next + flip * (after - next);
  ky = after + flip * (next - after);
  // Reciprocal instead of three divisions; every vertex sees the same shear, so the test
  // stays watertight.
  shearZ = iv[kz];
  shearX = dv[kx] * shearZ;
  shearY = dv[ky] * shearZ;
}

/// True for triangles with no usable surface: zero or near-zero area relative to their edges
/// (sine of the corner angle below 1e-5), or non-finite vertices. Queries skip them.
bool isDegenerate(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) noexcept;

/// Watertight ray/triangle hit: t in (tMin, tMax) and barycentrics, or false. Edges shared by
/// two triangles are never missed by both; degenerate triangles never hit. `frontFace`, when
/// given, is set on a hit: whether the ray met the counter-clockwise side (p0, p1, p2), from the
/// sign of the same determinant that decided the hit (it is minus the normal's component along
/// the ray, seen down the shear's axis with the winding kept).
inline bool intersectTriangle(const PreparedRay& ray, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                              float tMin, float tMax, float& t, float& u, float& v, bool* frontFace = nullptr) noexcept {
  const glm::vec3 a = p0 - ray.origin, b = p1 - ray.origin, c = p2 - ray.origin;
  const int kx = ray.kx, ky = ray.ky, kz = ray.kz;
  const float ax = a[kx] - ray.shearX * a[kz], ay = a[ky] - ray.shearY * a[kz];
  const float bx = b[kx] - ray.shearX * b[kz], by = b[ky] - ray.shearY * b[kz];
  const float cx = c[kx] - ray.shearX * c[kz], cy = c[ky] - ray.shearY * c[kz];
  float e0 = cx * by - cy * bx;
  float e1 = ax * cy - ay * cx;
  float e2 = bx * ay - by * ax;
  if (e0 == 0.0f || e1 == 0.0f || e2 == 0.0f) {
    // Edge cases decide watertightness: redo the 2D edge functions in double.
    e0 = float(double(cx) * double(by) - double(cy) * double(bx));
    e1 = float(double(ax) * double(cy) - double(ay) * double(cx));
    e2 = float(double(bx) * double(ay) - double(by) * double(ax));
  }
  if ((e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) && (e0 > 0.0f || e1 > 0.0f || e2 > 0.0f)) return false;
  const float det = e0 + e1 + e2;
  if (det == 0.0f || !std::isfinite(det)) return false;
  const float az = ray.shearZ * a[kz], bz = ray.shearZ * b[kz], cz = ray.shearZ * c[kz];
  const float tScaled = e0 * az + e1 * bz + e2 * cz;
  const float inv = 1.0f / det;
  const float hitT = tScaled * inv;
  if (!(hitT > tMin && hitT < tMax)) return false;
  t = hitT;
  u = e1 * inv;
  v = e2 * inv;
  if (frontFace) *frontFace = det > 0.0f;
  return true;
}

/// Closest point of a triangle to `p` (Ericson, Real-Time Collision Detection 5.1.5) and its
/// barycentrics; degenerate triangles give a point on their extent.
inline glm::vec3 closestPointOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                                 float& u, float& v) noexcept {
  const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return u = 0.0f, v = 0.0f, a;
  const glm::vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return u = 1.0f, v = 0.0f, b;
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
    const float w = d1 / (d1 - d3);
    return u = w, v = 0.0f, a + w * ab;
  }
  const glm::vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return u = 0.0f, v = 1.0f, c;
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
    const float w = d2 / (d2 - d6);
    return u = 0.0f, v = w, a + w * ac;
  }
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
    const float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return u = 1.0f - w, v = w, b + w * (c - b);
  }
  const float sum = va + vb + vc;
  if (!(sum > 0.0f)) return u = 0.0f, v = 0.0f, a;  // degenerate: every region test was a tie
  const float denom = 1.0f / sum;
  u = vb * denom;
  v = vc * denom;
  return a + ab * u + ac * v;
}

/// 1 + 2*gamma(3) (Ize 2013): a slab test's exit distance times this never culls a box that a
/// watertight triangle hit lies in. Walks compare a popped box's entry with the nearest hit
/// times the same factor, so a box the slab test would accept is not dropped either.
inline constexpr float kSlabExitMargin = 1.00000024f;

/// Ray/box slab test: entry distance, or +infinity when the box is missed within
/// [tMin, tMax]. Conservative by a few ulps so watertight triangle hits are never culled.
float intersectBox(const glm::vec3& origin, const glm::vec3& invDirection, const glm::vec3& bmin,
                   const glm::vec3& bmax, float tMin, float tMax) noexcept;


}  // namespace vt::collision
