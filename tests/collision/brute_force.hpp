#pragma once
// Brute-force references in double precision: every query checked against every triangle.
#include <cmath>
#include <limits>

#include <glm/glm.hpp>

#include "vt/collision/triangle.hpp"
#include "vt/scene/scene.hpp"

namespace vt::test {

struct BruteHit {
  double t = std::numeric_limits<double>::infinity();
  double distance = std::numeric_limits<double>::infinity();
  int object = -1, triangle = -1;
  double minBary = 0.0;  // smallest barycentric of the ray hit (near 0 = near an edge)
};

inline void worldTriangle(const Scene& scene, int object, int tri, glm::dvec3 p[3]) {
  const SceneObject& o = scene.objects[std::size_t(object)];
  const Mesh& mesh = scene.meshes[std::size_t(o.mesh)];
  const glm::dmat4 m(o.T_world_object);
  for (int k = 0; k < 3; ++k) {
    p[k] = glm::dvec3(m * glm::dvec4(glm::dvec3(mesh.vertices[mesh.indices[std::size_t(3 * tri + k)]].position), 1.0));
  }
}

inline bool degenerateInObject(const Scene& scene, int object, int tri) {
  const SceneObject& o = scene.objects[std::size_t(object)];
  const Mesh& mesh = scene.meshes[std::size_t(o.mesh)];
  glm::vec3 p[3];
  for (int k = 0; k < 3; ++k) p[k] = mesh.vertices[mesh.indices[std::size_t(3 * tri + k)]].position;
  glm::vec3 q[3];
  const glm::mat3 linear(o.T_world_object);
  for (int k = 0; k < 3; ++k) q[k] = linear * p[k];
  return collision::isDegenerate(p[0], p[1], p[2]) || collision::isDegenerate(q[0], q[1], q[2]);
}

/// Closest hit (Moller-Trumbore in double) over all non-degenerate triangles.
inline BruteHit bruteRay(const Scene& scene, glm::dvec3 o, glm::dvec3 d) {
  BruteHit best;
  for (int obj = 0; obj < int(scene.objects.size()); ++obj) {
    const Mesh& mesh = scene.meshes[std::size_t(scene.objects[std::size_t(obj)].mesh)];
    for (int tri = 0; tri < int(mesh.triangleCount()); ++tri) {
      if (degenerateInObject(scene, obj, tri)) continue;
      glm::dvec3 p[3];
      worldTriangle(scene, obj, tri, p);
      const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
      const glm::dvec3 h = glm::cross(d, e2);
      const double det = glm::dot(e1, h);
      if (std::abs(det) < 1e-300) continue;
      const glm::dvec3 s = o - p[0];
      const double u = glm::dot(s, h) / det;
      const glm::dvec3 q = glm::cross(s, e1);
      const double v = glm::dot(d, q) / det;
      const double t = glm::dot(e2, q) / det;
      if (u < 0 || v < 0 || u + v > 1 || t <= 0 || t >= best.t) continue;
      best.t = t;
      best.object = obj;
      best.triangle = tri;
      best.minBary = std::min({u, v, 1 - u - v});
    }
  }
  return best;
}

inline glm::dvec3 closestOnTriangle(glm::dvec3 p, const glm::dvec3 tri[3]) {
  // Minimum over the interior projection and the three edges: simple and independent.
  const glm::dvec3 a = tri[0], b = tri[1], c = tri[2];
  const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
  const glm::dvec3 proj = p - glm::dot(p - a, n) * n;
  auto inside = [&](glm::dvec3 q) {
    return glm::dot(glm::cross(b - a, q - a), n) >= 0 && glm::dot(glm::cross(c - b, q - b), n) >= 0 &&
           glm::dot(glm::cross(a - c, q - c), n) >= 0;
  };
  if (inside(proj)) return proj;
  auto onSegment = [&](glm::dvec3 s, glm::dvec3 e) {
    const double t = std::clamp(glm::dot(p - s, e - s) / glm::dot(e - s, e - s), 0.0, 1.0);
    return s + t * (e - s);
  };
  glm::dvec3 best = onSegment(a, b);
  for (glm::dvec3 q : {onSegment(b, c), onSegment(c, a)}) {
    if (glm::distance(q, p) < glm::distance(best, p)) best = q;
  }
  return best;
}

/// Nearest surface point over all non-degenerate triangles.
inline BruteHit bruteClosest(const Scene& scene, glm::dvec3 p) {
  BruteHit best;
  for (int obj = 0; obj < int(scene.objects.size()); ++obj) {
    const Mesh& mesh = scene.meshes[std::size_t(scene.objects[std::size_t(obj)].mesh)];
    for (int tri = 0; tri < int(mesh.triangleCount()); ++tri) {
      if (degenerateInObject(scene, obj, tri)) continue;
      glm::dvec3 w[3];
      worldTriangle(scene, obj, tri, w);
      const double d = glm::distance(closestOnTriangle(p, w), p);
      if (d < best.distance) {
        best.distance = d;
        best.object = obj;
        best.triangle = tri;
      }
    }
  }
  return best;
}

}  // namespace vt::test
