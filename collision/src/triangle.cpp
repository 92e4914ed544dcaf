#include "vt/collision/triangle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vt::collision {

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
  const float exit = std::min(std::min(tFar.x, tFar.y), std::min(tFar.z, tMax)) * kSlabExitMargin;
  return entry <= exit ? entry : std::numeric_limits<float>::infinity();
}

}  // namespace vt::collision
