#pragma once
// Random meshes and scenes for the collision tests, and the kernel levels each query test
// runs under (one ctest per level; a level the CPU lacks is skipped visibly).
#include <memory>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "test_support.hpp"
#include "vt/collision/simd.hpp"
#include "vt/scene/scene.hpp"

namespace vt::test {

// Sets a kernel level while it lives (active: the CPU has it) and restores the best one.
struct ScopedSimdLevel {
  bool active;
  explicit ScopedSimdLevel(collision::SimdLevel level) : active(collision::setSimdLevel(level)) {}
  ~ScopedSimdLevel() { collision::setSimdLevel(collision::bestSimdLevel()); }
};

inline glm::vec3 randomVec(std::mt19937& rng, float lo, float hi) {
  std::uniform_real_distribution<float> dist(lo, hi);
  return {dist(rng), dist(rng), dist(rng)};
}

// A soup of random triangles plus a bumpy grid; some triangles deliberately degenerate.
inline Mesh randomMesh(std::mt19937& rng, int triangles) {
  Mesh mesh;
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < triangles; ++i) {
    const glm::vec3 c = randomVec(rng, -1.0f, 1.0f);
    const float size = 0.05f + 0.4f * unit(rng);
    glm::vec3 p[3] = {c + randomVec(rng, -size, size), c + randomVec(rng, -size, size), c + randomVec(rng, -size, size)};
    if (i % 17 == 0) p[2] = p[1];                           // zero area
    if (i % 23 == 0) p[2] = p[0] + 2.0f * (p[1] - p[0]);  // collinear
    for (const auto& q : p) mesh.vertices.push_back({q, {0, 1, 0}, {unit(rng), unit(rng)}});
    for (int k = 0; k < 3; ++k) mesh.indices.push_back(std::uint32_t(3 * i + k));
  }
  return mesh;
}

inline glm::mat4 randomTransform(std::mt19937& rng, int kind) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  glm::mat4 m = glm::translate(glm::mat4(1.0f), randomVec(rng, -1.5f, 1.5f));
  m = glm::rotate(m, 6.28f * unit(rng), glm::normalize(randomVec(rng, -1.0f, 1.0f) + glm::vec3(0.01f)));
  if (kind == 1) m = glm::scale(m, glm::vec3(0.3f + 2.0f * unit(rng)));                    // uniform
  if (kind == 2) m = glm::scale(m, glm::vec3(0.3f, 1.0f, 2.0f) + randomVec(rng, 0.0f, 0.5f));  // non-uniform
  if (kind == 3) m = glm::scale(m, glm::vec3(-1.0f, 1.0f, 1.0f));                            // mirrored
  return m;
}

inline std::shared_ptr<Scene> randomScene(std::uint32_t seed) {
  std::mt19937 rng(seed);
  auto scene = std::make_shared<Scene>();
  const int meshCount = 1 + int(seed % 3);
  for (int i = 0; i < meshCount; ++i) scene->meshes.push_back(randomMesh(rng, 20 + int(rng() % 200)));
  scene->meshes.push_back(makePlane({1.0f, 1.0f}, 6));
  scene->meshes.push_back(Mesh{});  // an empty mesh must be harmless
  scene->materials.push_back({});
  const int objects = 1 + int(rng() % 5);
  for (int i = 0; i < objects; ++i) {
    SceneObject o;
    o.mesh = int(rng() % scene->meshes.size());
    o.material = 0;
    o.T_world_object = randomTransform(rng, int(rng() % 4));
    scene->objects.push_back(o);
  }
  return scene;
}

}  // namespace vt::test

// A kernel level as a type, named as ctest shows it: TEMPLATE_TEST_CASE(..., VT_KERNEL_LEVELS)
// makes one test case per level ("<name> - avx2").
template <vt::collision::SimdLevel L>
struct KernelLevel {
  static constexpr vt::collision::SimdLevel value = L;
};
using sse2 = KernelLevel<vt::collision::SimdLevel::Sse2>;
using avx2 = KernelLevel<vt::collision::SimdLevel::Avx2>;
using avx512 = KernelLevel<vt::collision::SimdLevel::Avx512>;
using avx512_all_queries = KernelLevel<vt::collision::SimdLevel::Avx512AllQueries>;
using avx512_on_avx2 = KernelLevel<vt::collision::SimdLevel::Avx512OnAvx2>;
#define VT_KERNEL_LEVELS sse2, avx2, avx512, avx512_all_queries, avx512_on_avx2

/// In a TEMPLATE_TEST_CASE over VT_KERNEL_LEVELS: queries use TestType's kernels for the rest
/// of the test case, which is skipped (VT_SKIP) where the CPU lacks them.
#define VT_USE_KERNEL_LEVEL()                                              \
  const ::vt::test::ScopedSimdLevel vtScopedLevel(TestType::value);       \
  if (!vtScopedLevel.active) VT_SKIP("this CPU cannot run the " << ::vt::collision::simdLevelName(TestType::value) << " kernels")
