#pragma once
// The haptics suite's scene and queries (vt_bench haptics), shared with the A/B program of
// scripts/collision-ab.sh so that both time the same work.
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "vt/collision/query.hpp"
#include "vt/scene/demo_scene.hpp"
#include "vt/scene/mesh.hpp"
#include "vt/scene/scene.hpp"

namespace vt::bench {

// A bumpy unit sphere of about 2 * slices * stacks triangles (a dense scanned-object stand-in).
inline std::shared_ptr<Scene> bumpySphereScene(int slices, int stacks) {
  auto scene = std::make_shared<Scene>();
  Mesh mesh = makeSphere(slices, stacks);
  for (Vertex& v : mesh.vertices) {
    const glm::vec3 n = v.position;
    v.position = n * (1.0f + 0.02f * std::sin(40.0f * n.x) * std::sin(40.0f * n.y) * std::sin(40.0f * n.z));
  }
  scene->meshes.push_back(std::move(mesh));
  scene->vibrationMaps.push_back(makePatternVibrationMap(Pattern::Wood, 256));
  Material material;
  material.vibrationMap = 0;
  scene->materials.push_back(material);
  scene->objects.push_back({"sphere", 0, 0, glm::mat4(1.0f)});
  return scene;
}

// Rays from a radius-3 shell toward points within radius 1.2 (most hit the sphere).
inline std::vector<collision::Ray> makeRays(std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g;
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<collision::Ray> rays(count);
  for (auto& r : rays) {
    const glm::vec3 o = 3.0f * glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
    const glm::vec3 target = 1.2f * std::cbrt(u(rng)) * glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
    r.origin = o;
    r.direction = glm::normalize(target - o);
  }
  return rays;
}

// Fingertip-sized spheres near the surface (about half touch it).
inline std::vector<collision::Sphere> makeSpheres(std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g;
  std::uniform_real_distribution<float> u(-0.03f, 0.03f);
  std::vector<collision::Sphere> spheres(count);
  for (auto& s : spheres) s = {(1.0f + u(rng)) * glm::normalize(glm::vec3(g(rng), g(rng), g(rng))), 0.01f};
  return spheres;
}

}  // namespace vt::bench
