#pragma once
// Query inputs and results shared by mesh- and scene-level collision.
#include <cstdint>
#include <limits>

#include <glm/glm.hpp>

namespace vt::collision {

inline constexpr std::uint32_t kNoHit = 0xffffffffu;

/// A ray segment origin + t * direction, t in (tMin, tMax).
struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};
  float tMin = 0.0f;
  float tMax = std::numeric_limits<float>::infinity();
};

/// Closest ray hit. Barycentrics: u weights the triangle's 2nd vertex, v the 3rd.
struct RayHit {
  float t = std::numeric_limits<float>::infinity();
  std::uint32_t object = kNoHit;    // scene object index (instance)
  std::uint32_t triangle = kNoHit;  // triangle index in the object's mesh
  float u = 0.0f, v = 0.0f;
  bool frontFace = false;           // the ray met the counter-clockwise (outer) side

  bool hit() const noexcept { return triangle != kNoHit; }
};

/// A sphere (a fingertip) in world space.
struct Sphere {
  glm::vec3 center{0.0f};
  float radius_m = 0.0f;
};

/// The surface point nearest a sphere's centre, when within the radius.
struct SphereContact {
  std::uint32_t object = kNoHit;
  std::uint32_t triangle = kNoHit;
  float u = 0.0f, v = 0.0f;        // barycentrics of `point` (as RayHit)
  glm::vec3 point{0.0f};           // closest surface point, world space
  glm::vec3 normal{0.0f, 1.0f, 0.0f};  // unit geometric normal of the triangle (outer side), world
  float distance_m = 0.0f;         // centre to point
  float depth_m = 0.0f;            // penetration: radius - distance, or radius + distance when the
                                   // centre is behind the surface
  bool hit() const noexcept { return triangle != kNoHit; }
};

}  // namespace vt::collision
