#pragma once
// Triangle tests returning barycentrics (u = weight of p1, v = weight of p2, p0 gets 1-u-v),
// which is exactly what UV lookup needs. Pure, allocation-free, any thread.
#include <glm/glm.hpp>

namespace vt::collision {

/// A ray prepared for the watertight triangle test (Woop, Benthin, Wald 2013) and slab tests.
struct PreparedRay {
  glm::vec3 origin;
  glm::vec3 direction;
  glm::vec3 invDirection;  // zero components replaced by a tiny value: no NaN in slab tests
  int kx = 0, ky = 1, kz = 2;
  glm::vec3 shear;  // Sx, Sy, Sz

  /// direction need not be normalised; hit distances are in units of |direction|.
  PreparedRay(const glm::vec3& origin, const glm::vec3& direction) noexcept;
};

/// True for triangles with no usable surface: zero or near-zero area relative to their edges
/// (sine of the corner angle below 1e-5), or non-finite vertices. Queries skip them.
bool isDegenerate(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) noexcept;

/// Watertight ray/triangle hit: t in (tMin, tMax) and barycentrics, or false. Edges shared by
/// two triangles are never missed by both; degenerate triangles never hit.
bool intersectTriangle(const PreparedRay& ray, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                       float tMin, float tMax, float& t, float& u, float& v) noexcept;

/// Closest point of a triangle to `p` (Ericson, Real-Time Collision Detection 5.1.5) and its
/// barycentrics; degenerate triangles give a point on their extent.
glm::vec3 closestPointOnTriangle(const glm::vec3& p, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                                 float& u, float& v) noexcept;

/// Ray/box slab test: entry distance, or a value > tMax when missed. Conservative by a few
/// ulps so watertight triangle hits are never culled by their box.
float intersectBox(const PreparedRay& ray, const glm::vec3& bmin, const glm::vec3& bmax, float tMin,
                   float tMax) noexcept;

}  // namespace vt::collision
