#include "vt/collision/triangle.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace vt::collision {

PreparedRay::PreparedRay(const glm::vec3& o, const glm::vec3& d) noexcept : origin(o), direction(d) {
  for (int a = 0; a < 3; ++a) {
    const float c = d[a] == 0.0f ? 1e-30f : d[a];
    invDirection[a] = 1.0f / c;
  }
  const glm::vec3 ad = glm::abs(d);
  kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  kx = (kz + 1) % 3;
  ky = (kx + 1) % 3;
  if (d[kz] < 0.0f) std::swap(kx, ky);  // keeps the winding, so the edge tests stay consistent
  const float dz = d[kz] == 0.0f ? 1e-30f : d[kz];
  shear = {d[kx] / dz, d[ky] / dz, 1.0f / dz};
}

bool isDegenerate(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) noexcept {
  const glm::vec3 e1 = p1 - p0, e2 = p2 - p0;
  const glm::vec3 n = glm::cross(e1, e2);
  const float n2 = glm::dot(n, n);
  const float scale = glm::dot(e1, e1) * glm::dot(e2, e2);
  return !std::isfinite(n2) || !std::isfinite(scale) || !(n2 > 1e-10f * scale);
}

bool intersectTriangle(const PreparedRay& ray, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                       float tMin, float tMax, float& t, float& u, float& v) noexcept {
  const glm::vec3 a = p0 - ray.origin, b = p1 - ray.origin, c = p2 - ray.origin;
  const int kx = ray.kx, ky = ray.ky, kz = ray.kz;
  const float sx = ray.shear.x, sy = ray.shear.y, sz = ray.shear.z;
  const float ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
  const float bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
  const float cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];
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
  const float az = sz * a[kz], bz = sz * b[kz], cz = sz * c[kz];
  const float tScaled = e0 * az + e1 * bz + e2 * cz;
  const float inv = 1.0f / det;
  const float hitT = tScaled * inv;
  if (!(hitT > tMin && hitT < tMax)) return false;
  t = hitT;
  u = e1 * inv;
  v = e2 * inv;
  return true;
}

glm::vec3 closestPointOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
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

float intersectBox(const PreparedRay& ray, const glm::vec3& bmin, const glm::vec3& bmax, float tMin,
                   float tMax) noexcept {
  const glm::vec3 t0 = (bmin - ray.origin) * ray.invDirection;
  const glm::vec3 t1 = (bmax - ray.origin) * ray.invDirection;
  const glm::vec3 tNear = glm::min(t0, t1), tFar = glm::max(t0, t1);
  const float entry = std::max(std::max(tNear.x, tNear.y), std::max(tNear.z, tMin));
  // 1 + 2*gamma(3) (Ize 2013): robust against rounding in the slab distances.
  const float exit = std::min(std::min(tFar.x, tFar.y), std::min(tFar.z, tMax)) * 1.00000024f;
  return entry <= exit ? entry : 3.4e38f;
}

}  // namespace vt::collision
