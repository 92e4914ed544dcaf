#include <catch2/catch.hpp>

#include <cstdlib>
#include <memory>

#include "test_support.hpp"
#include "vt/collision/collision_scene.hpp"
#include "vt/haptics/uv_lookup.hpp"
#include "vt/haptics/vibration_map.hpp"

using namespace vt;
using namespace vt::haptics;

TEST_CASE("Barycentric UV interpolation on a hand-built quad") {
  Mesh quad;
  quad.vertices = {{{0, 0, 0}, {0, 1, 0}, {0.0f, 0.0f}},
                   {{1, 0, 0}, {0, 1, 0}, {1.0f, 0.0f}},
                   {{1, 0, -1}, {0, 1, 0}, {1.0f, 1.0f}},
                   {{0, 0, -1}, {0, 1, 0}, {0.0f, 1.0f}}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  CHECK(interpolateUv(quad, 0, 0.0f, 0.0f) == glm::vec2(0.0f, 0.0f));
  CHECK(interpolateUv(quad, 0, 1.0f, 0.0f) == glm::vec2(1.0f, 0.0f));
  const glm::vec2 mid = interpolateUv(quad, 1, 0.25f, 0.5f);  // 0.25 * (1,1) + 0.5 * (0,1)
  CHECK(mid.x == Approx(0.25f));
  CHECK(mid.y == Approx(0.75f));
  // Out of range is a bug upstream: loud in checked builds, counted (and (0, 0)) in release.
  CHECK(vt::test::invariantHandled([&] {
    if (interpolateUv(quad, 7, 0.5f, 0.5f) != glm::vec2(0.0f)) std::abort();  // the fallback
  }));

  // End to end: a fingertip above (x, z) on the quad gets uv = (x, -z).
  auto scene = std::make_shared<Scene>();
  scene->meshes.push_back(quad);
  scene->materials.push_back({});
  scene->objects.push_back({"quad", 0, 0, glm::mat4(1.0f)});
  const collision::CollisionScene world(scene);
  for (const glm::vec2 xz : {glm::vec2(0.3f, -0.2f), glm::vec2(0.9f, -0.7f), glm::vec2(0.1f, -0.95f)}) {
    const collision::SphereContact c = world.sphereContact({{xz.x, 0.005f, xz.y}, 0.01f});
    REQUIRE(c.hit());
    const glm::vec2 uv = interpolateUv(scene->meshes[0], c.triangle, c.u, c.v);
    CHECK(uv.x == Approx(xz.x));
    CHECK(uv.y == Approx(-xz.y));
  }
}

TEST_CASE("Material uvTransform scales and offsets before wrap or clamp sampling") {
  glm::mat3 m(1.0f);
  m[0][0] = 2.0f;  // u' = 2u + 0.25
  m[1][1] = 3.0f;  // v' = 3v - 0.5
  m[2] = glm::vec3(0.25f, -0.5f, 1.0f);
  const glm::vec2 uv = applyUvTransform(m, {0.5f, 0.5f});
  CHECK(uv.x == Approx(1.25f));
  CHECK(uv.y == Approx(1.0f));
  // 4x1 ramp: texel centres at u = 0.125, 0.375, ...; u' = 1.25 wraps to 0.25 (between 0 and 1).
  const std::vector<float> ramp{0.0f, 0.25f, 0.5f, 0.75f};
  const VibrationMap map = vibrationMapFromFloats(4, 1, ramp, "ramp");
  CHECK(map.sample(uv, true) == Approx(0.125f));
  CHECK(map.sample(uv, false) == Approx(0.75f));
}
