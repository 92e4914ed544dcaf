#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "random_scene.hpp"
#include "vt/collision/collision_scene.hpp"

using namespace vt;
using namespace vt::collision;
using test::randomVec;

namespace {

// Every query kind, single and batched, over one world: what the levels must agree on.
struct Answers {
  std::vector<RayHit> rays, rayBatches;
  std::vector<SphereContact> contacts, contactBatches;
};

Answers answer(const CollisionScene& world, const std::vector<Ray>& rays, const std::vector<Sphere>& spheres) {
  Answers a;
  for (const Ray& r : rays) a.rays.push_back(world.intersect(r));
  for (const Sphere& s : spheres) a.contacts.push_back(world.sphereContact(s));
  a.rayBatches.resize(rays.size());
  a.contactBatches.resize(spheres.size());
  // Batches of 12 (two hands' contact points) and 16 (the batch limit) alternate.
  for (std::size_t i = 0, n = 12; i < rays.size(); i += n, n = n == 12 ? 16 : 12) {
    const std::size_t count = std::min(n, rays.size() - i);
    world.intersect({rays.data() + i, count}, {a.rayBatches.data() + i, count});
    world.sphereContacts({spheres.data() + i, count}, {a.contactBatches.data() + i, count});
  }
  return a;
}

void requireSame(const RayHit& a, const RayHit& b) {
  REQUIRE(a.object == b.object);
  REQUIRE(a.triangle == b.triangle);
  REQUIRE(a.t == b.t);
  REQUIRE(a.u == b.u);
  REQUIRE(a.v == b.v);
  REQUIRE(a.frontFace == b.frontFace);
}

void requireSame(const SphereContact& a, const SphereContact& b) {
  REQUIRE(a.object == b.object);
  REQUIRE(a.triangle == b.triangle);
  REQUIRE(a.u == b.u);
  REQUIRE(a.v == b.v);
  REQUIRE(a.point == b.point);
  REQUIRE(a.normal == b.normal);
  REQUIRE(a.distance_m == b.distance_m);
  REQUIRE(a.depth_m == b.depth_m);
}

// A bumpy sphere dense enough for merged leaves of every size up to the merged limit and
// several wide levels (random soups give shallow trees).
std::shared_ptr<Scene> bumpySphere() {
  auto scene = std::make_shared<Scene>();
  Mesh mesh = makeSphere(160, 80);
  for (Vertex& v : mesh.vertices) v.position *= 1.0f + 0.05f * std::sin(23.0f * v.position.x + 7.0f * v.position.z);
  scene->meshes.push_back(std::move(mesh));
  scene->materials.push_back({});
  scene->objects.push_back({"sphere", 0, 0, glm::mat4(1.0f)});
  return scene;
}

}  // namespace

TEMPLATE_TEST_CASE("Every kernel level returns the baseline kernels' answers bit for bit", "", avx2, avx512, avx512_all_queries, avx512_on_avx2) {
  VT_USE_KERNEL_LEVEL();
  std::vector<std::shared_ptr<Scene>> scenes{bumpySphere()};
  for (std::uint32_t seed : {11u, 12u, 13u}) scenes.push_back(test::randomScene(seed));
  const bool quantized = GENERATE(false, true);
  const int merged = GENERATE(16, kDefaultMergedLeafSize);  // a smaller limit, and the default
  int rayHits = 0, contacts = 0;
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    for (const int leafSize : {1, 4, 7}) {  // full, padded and mixed packs before merging
      INFO("scene " << s << " leaf size " << leafSize << " quantized nodes " << quantized << " merged " << merged);
      BuildConfig config{16, leafSize, 1.0f};
      config.mergedLeafSize = merged;
      config.raysInTurnsFromBytes = config.pointsInTurnsFromBytes = 0;  // batches walk in turns: the batched kernels
      config.floatNodesUpToTriangles = quantized ? 0 : SIZE_MAX;  // both node formats
      const CollisionScene world(scenes[s], config);
      std::mt19937 rng(17 + std::uint32_t(s));
      std::vector<Ray> rays;
      std::vector<Sphere> spheres;
      for (int i = 0; i < 1500; ++i) {
        const glm::vec3 origin = randomVec(rng, -3.0f, 3.0f);
        rays.push_back({origin, randomVec(rng, -0.7f, 0.7f) - origin});
        spheres.push_back({randomVec(rng, -1.3f, 1.3f), 0.05f + 0.3f * float(i % 4)});
      }
      rays[3].tMin = 0.5f;
      rays[8].tMax = 1.0f;
      // Rays from 1e5 to 1e38 away: edge functions exactly zero, infinite or NaN.
      for (int i = 0; i < 200; ++i) {
        const glm::vec3 target = randomVec(rng, -1.0f, 1.0f);
        const float distance = std::pow(10.0f, float(5 + i % 34));
        const glm::vec3 origin = target - glm::normalize(randomVec(rng, -1.0f, 1.0f)) * distance;
        rays.push_back({origin, target - origin});
        spheres.push_back({target, 0.2f});
      }
      REQUIRE(setSimdLevel(SimdLevel::Sse2));
      const Answers baseline = answer(world, rays, spheres);
      REQUIRE(setSimdLevel(TestType::value));
      const Answers level = answer(world, rays, spheres);
      for (std::size_t i = 0; i < rays.size(); ++i) {
        INFO("query " << i);
        requireSame(level.rays[i], baseline.rays[i]);
        requireSame(level.rayBatches[i], baseline.rayBatches[i]);
        requireSame(level.contacts[i], baseline.contacts[i]);
        requireSame(level.contactBatches[i], baseline.contactBatches[i]);
        rayHits += baseline.rays[i].hit();
        contacts += baseline.contacts[i].hit();
      }
    }
  }
  CHECK(rayHits > 3000);
  CHECK(contacts > 3000);
}

TEST_CASE("The kernels start at the best level the CPU and OS support, and refuse the others") {
#if defined(__x86_64__)
  // libgcc's own detection (CPUID and the OS-saved register state) as the independent answer.
  const bool hasAvx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
  const bool hasAvx2 = hasAvx512 || __builtin_cpu_supports("avx2");
  CHECK(bestSimdLevel() == (hasAvx512 ? SimdLevel::Avx512 : hasAvx2 ? SimdLevel::Avx2 : SimdLevel::Sse2));
#endif
  CHECK(simdLevel() == bestSimdLevel());
  for (const SimdLevel level : kSimdLevels) {
    INFO(simdLevelName(level));
    const test::ScopedSimdLevel scoped(level);
    CHECK(scoped.active == simdLevelSupported(level));
    CHECK(simdLevel() == (scoped.active ? level : bestSimdLevel()));
  }
  CHECK(simdLevelSupported(SimdLevel::Sse2));
  CHECK(simdLevelSupported(SimdLevel::Avx512OnAvx2) == simdLevelSupported(SimdLevel::Avx2));
  CHECK(simdLevelSupported(SimdLevel::Avx512AllQueries) == simdLevelSupported(SimdLevel::Avx512));
}
