#include "vt/collision/triangle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vt::collision {

glm::vec3 safeInverse(const glm::vec3& d) noexcept {
  glm::vec3 inv;
  for (int a = 0; a < 3; ++a) inv[a] = 1.0f / (d[a] == 0.0f ? 1e-30f : d[a]);
  return inv;
}

PreparedRay::PreparedRay(const glm::vec3& o, const glm::vec3& d) noexcept
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

bool isDegenerate(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) noexcept {
  const glm::vec3 e1 = p1 - p0, e2 = p2 - p0;
  const glm::vec3 n = glm::cross(e1, e2);
  const float n2 = glm::dot(n, n);
  const float scale = glm::dot(e1, e1) * glm::dot(e2, e2);
  return !std::isfinite(n2) || !std::isfinite(scale) || !(n2 > 1e-10f * scale);
}

float intersectBox(const glm::vec3& origin, const glm::vec3& invDirection, const glm::vec3& bmin,
                   const glm::vec3& bmax, float tMin, float tMax) noexcept {
  const glm::vec3 t0 = (bmin - origin) * invDirection;
  const glm::vec3 t1 = (bmax - origin) * invDirection;
  const glm::vec3 tNear = glm::min(t0, t1), tFar = glm::max(t0, t1);
  const float entry = std::max(std::max(tNear.x, tNear.y), std::max(tNear.z, tMin));
  // 1 + 2*gamma(3) (Ize 2013): robust against rounding in the slab distances.
  const float exit = std::min(std::min(tFar.x, tFar.y), std::min(tFar.z, tMax)) * 1.00000024f;
  return entry <= exit ? entry : std::numeric_limits<float>::infinity();
}

}  // namespace vt::collision
