#pragma once
// The A/B program's shared types: the workload both sides answer (made once, by ab_main.cpp)
// and the interface each side's CollisionScene is driven through. Plain types only: the two
// sides are compiled in different namespaces and meet here.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

namespace ab {

// Build: the rays' workload, timing the build. SphereBatches: twelve spheres a call (two hands).
enum class Kind { Rays, RayBatches, Spheres, SphereBatches, Build };

struct Workload {
  Kind kind = Kind::Rays;
  std::vector<glm::vec3> positions;     // mesh vertices
  std::vector<std::uint32_t> indices;   // triangles
  std::vector<glm::vec3> origins;       // ray origins or sphere centres
  std::vector<glm::vec3> directions;    // ray directions (rays only)
  float radius = 0.01f;                 // sphere radius (spheres only)
};

struct World {
  virtual ~World() = default;
  /// Answers every query once (nearest distance, -1 for none).
  virtual void answer(const Workload& work, float* answers) = 0;
  /// Builds its CollisionScene anew after freeing the old one, as a scene reload does; returns
  /// the thread CPU seconds of the build alone (as vt_bench haptics times builds).
  virtual double rebuild() = 0;
};

}  // namespace ab

// A side's scene, not built yet: ab_main.cpp makes both sides' meshes before either builds.
// Made after side A's first build, side B's mesh took heap memory that build had freed, and
// B's builds then ran 9 - 11 % faster than A's with the same code on both sides (either
// order of making them; the mechanism, in glibc's heap and the kernel's pages, not pinned down).
std::unique_ptr<ab::World> makeWorldA(const ab::Workload& work);
std::unique_ptr<ab::World> makeWorldB(const ab::Workload& work);
