#include <catch2/catch.hpp>

#include <bit>
#include <memory>
#include <random>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "brute_force.hpp"
#include "random_scene.hpp"
#include "vt/collision/collision_scene.hpp"

using namespace vt;
using namespace vt::collision;
using test::randomMesh;
using test::randomScene;
using test::randomVec;

namespace {

// The world position a query reports through (object, triangle, barycentrics).
glm::dvec3 pointFromBarycentrics(const Scene& scene, std::uint32_t object, std::uint32_t tri, float u, float v) {
  glm::dvec3 p[3];
  test::worldTriangle(scene, int(object), int(tri), p);
  return (1.0 - u - v) * p[0] + double(u) * p[1] + double(v) * p[2];
}

void checkRays(const Scene& scene, const CollisionScene& world, std::mt19937& rng, int rays) {
  int edgeMisses = 0;
  for (int i = 0; i < rays; ++i) {
    Ray ray;
    ray.origin = randomVec(rng, -4.0f, 4.0f);
    ray.direction = randomVec(rng, -1.0f, 1.0f) - 0.3f * ray.origin;
    const RayHit hit = world.intersect(ray);
    const test::BruteHit brute = test::bruteRay(scene, ray.origin, ray.direction);
    if (hit.hit() != (brute.object >= 0)) {
      // Only grazing hits within rounding of an edge may disagree.
      REQUIRE(brute.object >= 0);
      REQUIRE(brute.minBary < 1e-4);
      ++edgeMisses;
      continue;
    }
    if (!hit.hit()) continue;
    REQUIRE(hit.t == Approx(brute.t).epsilon(1e-4).margin(1e-5));
    const glm::dvec3 expected = glm::dvec3(ray.origin) + double(hit.t) * glm::dvec3(ray.direction);
    REQUIRE(glm::distance(pointFromBarycentrics(scene, hit.object, hit.triangle, hit.u, hit.v), expected) <
            1e-3 * (1.0 + glm::length(expected)));
    glm::dvec3 p[3];
    test::worldTriangle(scene, int(hit.object), int(hit.triangle), p);
    const double det = glm::determinant(glm::dmat3(scene.objects[hit.object].T_world_object));
    const glm::dvec3 outward = glm::cross(p[1] - p[0], p[2] - p[0]) * (det < 0 ? -1.0 : 1.0);
    CHECK(hit.frontFace == (glm::dot(outward, glm::dvec3(ray.direction)) < 0.0));
  }
  CHECK(edgeMisses <= rays / 100);
}

void checkSpheres(const Scene& scene, const CollisionScene& world, std::mt19937& rng, int queries) {
  std::uniform_real_distribution<float> radius(0.01f, 0.6f);
  for (int i = 0; i < queries; ++i) {
    const Sphere sphere{randomVec(rng, -2.5f, 2.5f), radius(rng)};
    const SphereContact c = world.sphereContact(sphere);
    const test::BruteHit brute = test::bruteClosest(scene, sphere.center);
    const double r = sphere.radius_m;
    if (std::abs(brute.distance - r) < 1e-4) continue;  // on the boundary: either answer is right
    REQUIRE(c.hit() == (brute.distance < r));
    if (!c.hit()) continue;
    if (std::abs(c.distance_m - brute.distance) > 2e-5) {
      glm::dvec3 w[3];
      test::worldTriangle(scene, int(c.object), int(c.triangle), w);
      const double d = glm::distance(test::closestOnTriangle(sphere.center, w), glm::dvec3(sphere.center));
      FAIL("obj " << c.object << " tri " << c.triangle << " brute on that tri " << d << " brute best obj " << brute.object << " tri " << brute.triangle << " degenerate " << test::degenerateInObject(scene, int(c.object), int(c.triangle)));
    }
    REQUIRE(glm::distance(glm::dvec3(c.point), glm::dvec3(sphere.center)) == Approx(c.distance_m).margin(2e-5));
    REQUIRE(glm::distance(pointFromBarycentrics(scene, c.object, c.triangle, c.u, c.v), glm::dvec3(c.point)) < 1e-4);
    REQUIRE(glm::length(c.normal) == Approx(1.0f).margin(1e-4));
    REQUIRE(c.depth_m >= r - c.distance_m - 1e-5);
    REQUIRE(c.depth_m <= r + c.distance_m + 1e-5);
  }
}

// Every primitive of `boxes` is in exactly one leaf of `wide`, inside that leaf's child box;
// onLeaf(node, slot) is called on every leaf for the caller's own checks.
template <class Nodes, class OnLeaf>
void checkLeavesHoldEachPrimitiveOnce(const Nodes& wide, const Bvh& bvh, const std::vector<Aabb>& boxes,
                                      OnLeaf&& onLeaf) {
  std::vector<int> seen(boxes.size(), 0);
  for (const auto& node : wide) {
    for (int i = 0; i < kWidth; ++i) {
      if (node.count[i] == WideNode::kEmpty || node.count[i] == 0) continue;
      const Aabb box = node.childBox(i);
      for (std::uint32_t k = 0; k < node.count[i]; ++k) {
        const std::uint32_t p = bvh.primIds.at(node.child[i] + k);
        ++seen[p];
        REQUIRE(glm::all(glm::lessThanEqual(box.min, boxes[p].min)));
        REQUIRE(glm::all(glm::greaterThanEqual(box.max, boxes[p].max)));
      }
      onLeaf(node, i);
    }
  }
  for (int s : seen) REQUIRE(s == 1);
}

// Both ways a mesh BVH answers a batch: in turns (as on large meshes), and one query after
// another (as on meshes that stay in cache, these tests' default).
BuildConfig batchesInTurns(bool inTurns, BuildConfig config = {}) {
  if (inTurns) config.raysInTurnsFromBytes = config.pointsInTurnsFromBytes = 0;
  return config;
}

// Both node formats: float planes (as on meshes whose nodes stay small, these tests' default)
// and byte planes (as on large meshes).
BuildConfig nodesQuantized(bool quantized, BuildConfig config = {}) {
  config.floatNodesUpToTriangles = quantized ? 0 : SIZE_MAX;
  return config;
}

}  // namespace

TEMPLATE_TEST_CASE("Ray and sphere queries match brute force over random meshes and transforms", "", VT_KERNEL_LEVELS) {
  VT_USE_KERNEL_LEVEL();
  const bool quantized = GENERATE(false, true);
  INFO("quantized nodes: " << quantized);
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    INFO("seed " << seed);
    const auto scene = randomScene(seed);
    const CollisionScene world(scene, nodesQuantized(quantized, {seed % 2 ? 8 : 32, int(1 + seed % 8), 1.0f}));
    std::mt19937 rng(seed * 7919u);
    checkRays(*scene, world, rng, 300);
    checkSpheres(*scene, world, rng, 300);
  }
}

TEMPLATE_TEST_CASE("Batched fingertip contacts and rays equal one query each", "", VT_KERNEL_LEVELS) {
  VT_USE_KERNEL_LEVEL();
  const bool inTurns = GENERATE(false, true), quantized = GENERATE(false, true);
  INFO("batches in turns: " << inTurns << ", quantized nodes: " << quantized);
  const auto scene = randomScene(7);
  const CollisionScene world(scene, batchesInTurns(inTurns, nodesQuantized(quantized)));
  std::mt19937 rng(3);
  std::vector<Sphere> spheres;
  for (int i = 0; i < 64; ++i) spheres.push_back({randomVec(rng, -2.0f, 2.0f), 0.3f});
  std::vector<SphereContact> batch(spheres.size());
  world.sphereContacts(spheres, batch);
  int hits = 0;
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const SphereContact single = world.sphereContact(spheres[i]);
    CHECK(batch[i].triangle == single.triangle);
    CHECK(batch[i].object == single.object);
    CHECK(batch[i].distance_m == single.distance_m);
    hits += single.hit();
  }
  CHECK(hits > 0);
  std::vector<Ray> rays;
  for (int i = 0; i < 64; ++i) {
    const glm::vec3 origin = randomVec(rng, -3.0f, 3.0f);
    rays.push_back({origin, randomVec(rng, -0.5f, 0.5f) - origin});  // towards the objects
  }
  rays[5].tMin = 0.5f;
  rays[9].tMax = 1.0f;
  std::vector<RayHit> rayBatch(rays.size());
  world.intersect(rays, rayBatch);
  int rayHits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const RayHit single = world.intersect(rays[i]);
    CHECK(rayBatch[i].triangle == single.triangle);
    CHECK(rayBatch[i].object == single.object);
    CHECK(rayBatch[i].t == single.t);
    CHECK(rayBatch[i].frontFace == single.frontFace);
    rayHits += single.hit();
  }
  CHECK(rayHits > 0);
}

TEMPLATE_TEST_CASE("Rays through shared edges and vertices of a grid never fall through", "", VT_KERNEL_LEVELS) {
  VT_USE_KERNEL_LEVEL();
  auto scene = std::make_shared<Scene>();
  scene->meshes.push_back(makePlane({1.0f, 1.0f}, 8));
  scene->materials.push_back({});
  scene->objects.push_back({"plane", 0, 0, glm::mat4(1.0f)});
  const bool quantized = GENERATE(false, true);
  INFO("quantized nodes: " << quantized);
  const CollisionScene world(scene, nodesQuantized(quantized));
  int tested = 0;
  for (int i = 0; i <= 16; ++i) {
    for (int j = 0; j <= 16; ++j) {
      // Every grid vertex and every edge midpoint (steps of half a cell), from above and below.
      const float x = -0.5f + float(i) / 16.0f, z = -0.5f + float(j) / 16.0f;
      for (float dir : {-1.0f, 1.0f}) {
        const RayHit hit = world.intersect({{x * 0.999f, -dir, z * 0.999f}, {0.0f, dir, 0.0f}});
        REQUIRE(hit.hit());
        CHECK(hit.t == Approx(1.0f));
        CHECK(hit.frontFace == (dir < 0.0f));
        ++tested;
      }
    }
  }
  CHECK(tested == 578);
}

TEMPLATE_TEST_CASE("A ray meets the front face from the object's outer side under mirrors and non-uniform scale", "",
                   VT_KERNEL_LEVELS) {
  VT_USE_KERNEL_LEVEL();
  // makePlane's triangles face +y in the object frame. A mirror that is a similarity keeps the
  // shared BVH (facing judged in the object frame); one with non-uniform scale is baked into a
  // private BVH whose winding it reverses, which the instance's mirrored flag must undo.
  const glm::mat4 transforms[] = {
      glm::mat4(1.0f),
      glm::scale(glm::mat4(1.0f), {-1.0f, 1.0f, 1.0f}),  // mirror, similarity
      glm::scale(glm::mat4(1.0f), {-2.0f, 1.0f, 1.0f}),  // mirror, baked
      glm::scale(glm::mat4(1.0f), {1.0f, -3.0f, 1.0f}),  // mirror across the plane's normal, baked
      glm::scale(glm::mat4(1.0f), {2.0f, 1.0f, 0.5f}),   // no mirror, baked
  };
  const bool quantized = GENERATE(false, true);
  INFO("quantized nodes: " << quantized);
  for (const glm::mat4& T : transforms) {
    auto scene = std::make_shared<Scene>();
    scene->meshes.push_back(makePlane({1.0f, 1.0f}, 4));
    scene->materials.push_back({});
    scene->objects.push_back({"plane", 0, 0, glm::translate(glm::mat4(1.0f), {0.3f, -0.2f, 0.1f}) * T});
    const CollisionScene world(scene, nodesQuantized(quantized));
    const glm::mat4& M = scene->objects[0].T_world_object;
    const glm::vec3 target(M * glm::vec4(0.11f, 0.0f, 0.23f, 1.0f));  // inside a cell, off its diagonal
    const glm::vec3 outward = glm::normalize(glm::transpose(glm::inverse(glm::mat3(M))) * glm::vec3(0.0f, 1.0f, 0.0f));
    const RayHit fromOutside = world.intersect({target + 2.0f * outward, -outward});
    const RayHit fromInside = world.intersect({target - 2.0f * outward, outward});
    REQUIRE(fromOutside.hit());
    REQUIRE(fromInside.hit());
    CHECK(fromOutside.frontFace);
    CHECK_FALSE(fromInside.frontFace);
  }
}

TEST_CASE("A prepared ray inverts its direction and shears onto its largest axis, keeping the winding, ties and signed zeros") {
  // The definition the branch-free setup must keep: kz the axis of the largest |component|
  // (x before y before z on ties), then the next two axes in cyclic order, swapped when the
  // direction points down kz.
  const float values[] = {-2.0f, -1.0f, -0.0f, 0.0f, 1.0f, 2.0f, 1e-30f, -3e38f};
  int tested = 0;
  for (float x : values) {
    for (float y : values) {
      for (float z : values) {
        const glm::vec3 d(x, y, z);
        const glm::vec3 a = glm::abs(d);
        const int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
        int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
        if (d[kz] < 0.0f) std::swap(kx, ky);
        const PreparedRay ray(glm::vec3(0.0f), d);
        INFO("direction " << x << " " << y << " " << z);
        REQUIRE(ray.kz == kz);
        REQUIRE(ray.kx == kx);
        REQUIRE(ray.ky == ky);
        const glm::vec3 inv = ray.invDirection;
        for (int axis = 0; axis < 3; ++axis) {  // 1 / d, a zero of either sign taken as +1e-30
          const float expected = 1.0f / (d[axis] == 0.0f ? 1e-30f : d[axis]);
          REQUIRE(std::bit_cast<std::uint32_t>(inv[axis]) == std::bit_cast<std::uint32_t>(expected));
        }
        REQUIRE(std::bit_cast<std::uint32_t>(ray.shearZ) == std::bit_cast<std::uint32_t>(inv[kz]));
        REQUIRE(std::bit_cast<std::uint32_t>(ray.shearX) == std::bit_cast<std::uint32_t>(d[kx] * inv[kz]));
        REQUIRE(std::bit_cast<std::uint32_t>(ray.shearY) == std::bit_cast<std::uint32_t>(d[ky] * inv[kz]));
        ++tested;
      }
    }
  }
  CHECK(tested == 512);
}

TEMPLATE_TEST_CASE("Sphere contact reports depth normal and barycentrics on a hand-built quad", "", VT_KERNEL_LEVELS) {
  VT_USE_KERNEL_LEVEL();
  auto scene = std::make_shared<Scene>();
  scene->meshes.push_back(makePlane({2.0f, 2.0f}, 1));
  scene->materials.push_back({});
  scene->objects.push_back({"floor", 0, 0, glm::translate(glm::mat4(1.0f), {0.0f, 0.5f, 0.0f})});
  const CollisionScene world(scene);
  const SphereContact above = world.sphereContact({{0.25f, 0.51f, 0.25f}, 0.02f});
  REQUIRE(above.hit());
  CHECK(above.point.x == Approx(0.25f));
  CHECK(above.point.y == Approx(0.5f));
  CHECK(above.depth_m == Approx(0.01f).margin(1e-6));
  CHECK(above.normal.y == Approx(1.0f));
  const SphereContact below = world.sphereContact({{0.25f, 0.495f, 0.25f}, 0.02f});
  REQUIRE(below.hit());
  CHECK(below.depth_m == Approx(0.025f).margin(1e-6));  // centre sank under the surface
  CHECK_FALSE(world.sphereContact({{0.25f, 0.53f, 0.25f}, 0.02f}).hit());
  CHECK_FALSE(world.sphereContact({{0.25f, 0.51f, 0.25f}, 0.0f}).hit());
}

TEMPLATE_TEST_CASE("Empty scenes meshes and all-degenerate meshes never report hits", "", VT_KERNEL_LEVELS) {
  VT_USE_KERNEL_LEVEL();
  const CollisionScene none;
  CHECK_FALSE(none.intersect({}).hit());
  CHECK_FALSE(none.sphereContact({{0, 0, 0}, 1.0f}).hit());

  auto scene = std::make_shared<Scene>();
  Mesh flat;
  for (int i = 0; i < 9; ++i) flat.vertices.push_back({{float(i), 0.0f, 0.0f}});
  flat.indices = {0, 1, 2, 3, 4, 5, 6, 7, 8, 0, 0, 0};  // collinear and repeated vertices
  scene->meshes = {Mesh{}, flat};
  scene->materials.push_back({});
  scene->objects = {{"empty", 0, 0, glm::mat4(1.0f)}, {"flat", 1, 0, glm::mat4(1.0f)}};
  const CollisionScene world(scene);
  CHECK_FALSE(world.intersect({{1.0f, 1.0f, 0.0f}, {0.0f, -1.0f, 0.0f}}).hit());
  CHECK_FALSE(world.sphereContact({{1.0f, 0.0f, 0.0f}, 1.0f}).hit());
}

TEST_CASE("Bad meshes are rejected with the mesh named") {
  auto scene = std::make_shared<Scene>();
  Mesh bad;
  bad.vertices.resize(3);
  bad.indices = {0, 1, 7};
  scene->meshes.push_back(bad);
  CHECK_THROWS_WITH(CollisionScene(scene), Catch::Contains("triangle 0 uses vertex 7"));
}

TEMPLATE_TEST_CASE("Pathologically deep meshes stay within the traversal stacks and match brute force", "", VT_KERNEL_LEVELS) {
  VT_USE_KERNEL_LEVEL();
  // Triangles at exponentially shrinking offsets: a pure SAH split would chain one per level.
  auto scene = std::make_shared<Scene>();
  Mesh mesh;
  for (int i = 0; i < 120; ++i) {
    const float x = std::ldexp(1.0f, -i / 2);
    const auto base = std::uint32_t(mesh.vertices.size());
    mesh.vertices.push_back({{x, 0.0f, 0.0f}});
    mesh.vertices.push_back({{x + 0.5f * x, 0.0f, 0.1f}});
    mesh.vertices.push_back({{x, 0.1f, 0.05f}});
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
  }
  scene->meshes.push_back(mesh);
  scene->materials.push_back({});
  scene->objects.push_back({"deep", 0, 0, glm::mat4(1.0f)});
  const bool quantized = GENERATE(false, true);
  INFO("quantized nodes: " << quantized);
  const CollisionScene world(scene, nodesQuantized(quantized));
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 500; ++i) {
    const glm::vec3 p{std::ldexp(u(rng), -int(rng() % 40)), 0.05f * u(rng), 0.05f * u(rng)};
    const SphereContact c = world.sphereContact({p, 0.05f});
    const test::BruteHit brute = test::bruteClosest(*scene, p);
    REQUIRE(c.hit() == (brute.distance < 0.05));
    if (c.hit()) REQUIRE(c.distance_m == Approx(brute.distance).margin(1e-6));
    const Ray ray{{p.x, 1.0f, p.z}, {0.0f, -1.0f, 0.0f}};
    const test::BruteHit bruteRay = test::bruteRay(*scene, ray.origin, ray.direction);
    const RayHit hit = world.intersect(ray);
    if (bruteRay.object >= 0 && bruteRay.minBary > 1e-4) REQUIRE(hit.t == Approx(bruteRay.t).epsilon(1e-4));
  }
}

TEST_CASE("Wide nodes reference every triangle exactly once") {
  const Mesh mesh = makeSphere(40, 20);
  BuildConfig config{16, 3, 2.0f};
  config.mergedLeafSize = GENERATE(0, 16, kMaxWideLeafSize);  // the default, smaller, the largest
  const int merged = config.mergedLeafSize > 0 ? config.mergedLeafSize : kDefaultMergedLeafSize;
  INFO("merged leaf size " << merged);
  const MeshBvh bvh(mesh, "sphere", config);
  std::vector<int> seen(bvh.slotCount(), 0);
  int largest = 0;
  for (const WideNode& node : bvh.nodes()) {
    for (int i = 0; i < kWidth; ++i) {
      if (node.count[i] == WideNode::kEmpty || node.count[i] == 0) continue;
      largest = std::max(largest, int(node.count[i]));
      REQUIRE(node.count[i] <= std::max(3, merged));  // leaves, or merged subtrees
      REQUIRE(node.child[i] % kPackLanes == 0);  // each leaf starts a pack
      for (std::uint32_t k = 0; k < node.count[i]; ++k) ++seen.at(node.child[i] + k);
    }
  }
  // Every slot is one triangle's, or padding up to the end of its leaf's last pack.
  REQUIRE(std::count(seen.begin(), seen.end(), 1) == std::ptrdiff_t(bvh.triangleCount()));
  REQUIRE(std::count(seen.begin(), seen.end(), 0) == std::ptrdiff_t(bvh.slotCount() - bvh.triangleCount()));
  CHECK(bvh.triangleCount() + 2 * 40 == mesh.triangleCount());  // the pole triangles are degenerate
  CHECK(largest > merged / 2);  // the limit is the one asked for: leaves grow up to it
}

TEST_CASE("Collapsing merges small subtrees into leaves that keep every primitive once, split where slots are free") {
  std::mt19937 rng(5);
  std::vector<Aabb> boxes;
  for (int i = 0; i < 500; ++i) {
    const glm::vec3 c = randomVec(rng, -5.0f, 5.0f);
    boxes.push_back({c - 0.05f, c + 0.1f});
  }
  const Bvh bvh = buildBvh(boxes, {16, 1, 1.0f});  // one primitive per binary leaf
  std::size_t unmergedLeaves = 0;
  for (const std::uint32_t merge : {0u, 4u, 8u}) {
    std::size_t leaves = 0, largest = 0;
    checkLeavesHoldEachPrimitiveOnce(collapseToWide(bvh, merge), bvh, boxes, [&](const WideNode& node, int i) {
      // A node with a free slot has no merged leaf left to split (one primitive per binary leaf).
      const bool full = std::none_of(node.count, node.count + kWidth, [](std::uint8_t n) { return n == WideNode::kEmpty; });
      if (!full) REQUIRE(node.count[i] == 1);
      REQUIRE(node.count[i] <= std::max(1u, merge));
      ++leaves;
      largest = std::max<std::size_t>(largest, node.count[i]);
    });
    if (merge == 0) {
      REQUIRE(leaves == boxes.size());
      unmergedLeaves = leaves;
    } else {
      CHECK(largest == merge);
      CHECK(leaves < unmergedLeaves);
    }
  }
}

TEST_CASE("Wide child boxes hold their primitives at every scale, denormal extents and huge ones included") {
  // From 1e-36 down the boxes' extents are denormal; every child box must still hold its
  // primitives.
  for (const float scale : {1.0f, 1e-20f, 1e-36f, 1e-41f, 1e-44f, 1e30f}) {
    INFO("scale " << scale);
    std::mt19937 rng(11);
    std::vector<Aabb> boxes;
    for (int i = 0; i < 400; ++i) {
      const glm::vec3 c = randomVec(rng, -5.0f, 5.0f) * scale;
      boxes.push_back({c, c + glm::abs(randomVec(rng, 0.0f, 0.3f)) * scale});
    }
    const Bvh bvh = buildBvh(boxes, {16, 2, 1.0f});
    checkLeavesHoldEachPrimitiveOnce(collapseToWide<WideNode>(bvh, 4), bvh, boxes, [](const WideNode&, int) {});
    // Byte planes too: the decode check and the scale doubling behind it (from 2^-126 down a
    // scale is applied by division instead of its reciprocal).
    checkLeavesHoldEachPrimitiveOnce(collapseToWide<QuantizedWideNode>(bvh, 4), bvh, boxes,
                                     [](const QuantizedWideNode&, int) {});
  }
}

TEMPLATE_TEST_CASE("Packed leaves give the scalar triangle tests' nearest hits bit for bit", "", VT_KERNEL_LEVELS) {
  VT_USE_KERNEL_LEVEL();
  std::mt19937 rng(23);
  const Mesh mesh = randomMesh(rng, 300);  // with zero-area and collinear triangles
  const bool quantized = GENERATE(false, true);
  INFO("quantized nodes: " << quantized);
  for (const int leafSize : {1, 3, 5, 8}) {  // packs full, partly padded, and two per leaf
    INFO("leaf size " << leafSize);
    const MeshBvh bvh(mesh, "soup", nodesQuantized(quantized, {16, leafSize, 1.0f}));
    auto corner = [&](std::uint32_t triangle, int k) { return mesh.vertices[mesh.indices[3 * triangle + k]].position; };
    int rayHits = 0, pointHits = 0;
    for (int i = 0; i < 300; ++i) {
      const glm::vec3 origin = randomVec(rng, -2.0f, 2.0f);
      const PreparedRay ray(origin, randomVec(rng, -0.5f, 0.5f) - origin);
      float bestT = 1e30f;
      std::uint32_t bestTriangle = kNoHit;
      const glm::vec3 p = randomVec(rng, -1.5f, 1.5f);
      float bestD2 = 0.25f;
      std::uint32_t nearest = kNoHit;
      for (std::uint32_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::vec3 a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
        if (isDegenerate(a, b, c)) continue;
        float hitT, u, v;
        if (intersectTriangle(ray, a, b, c, 0.0f, bestT, hitT, u, v)) bestT = hitT, bestTriangle = t;
        const glm::vec3 q = closestPointOnTriangle(p, a, b, c, u, v);
        const float d2 = glm::dot(q - p, q - p);
        if (d2 < bestD2) bestD2 = d2, nearest = t;
      }
      MeshHit hit;
      REQUIRE(bvh.intersect(ray, 0.0f, hit, 1e30f) == (bestTriangle != kNoHit));
      if (bestTriangle != kNoHit) {
        REQUIRE(hit.t == bestT);  // exact: the same operations in the same order
        const TrianglePositions t = bvh.slotTriangle(hit.slot);
        REQUIRE(t.p0 == corner(hit.triangle, 0));
        ++rayHits;
      }
      MeshHit point;
      REQUIRE(bvh.closestPoint(p, 0.25f, point) == (nearest != kNoHit));
      if (nearest != kNoHit) {
        REQUIRE(point.t == bestD2);
        REQUIRE(glm::dot(point.point - p, point.point - p) == bestD2);
        ++pointHits;
      }
    }
    CHECK(rayHits > 50);
    CHECK(pointHits > 50);
    // Rays from far away: the vertices relative to the origin lose their differences to
    // rounding (edge functions exactly zero) or their edge functions overflow (infinite, or NaN
    // from inf - inf), which the packed steps decide by sign bits and the scalar test by
    // comparisons. Every outcome must still match.
    int farHits = 0;
    for (int i = 0; i < 400; ++i) {
      const float distance = std::pow(10.0f, float(5 + i % 34));  // 1e5 ... 1e38
      const glm::vec3 target = randomVec(rng, -0.5f, 0.5f);
      const glm::vec3 origin = target - glm::normalize(randomVec(rng, -1.0f, 1.0f)) * distance;
      const PreparedRay ray(origin, target - origin);
      float bestT = 2.0f;
      std::uint32_t bestTriangle = kNoHit;
      for (std::uint32_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::vec3 a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
        float hitT, u, v;
        if (!isDegenerate(a, b, c) && intersectTriangle(ray, a, b, c, 0.0f, bestT, hitT, u, v)) {
          bestT = hitT, bestTriangle = t;
        }
      }
      INFO("ray " << i << " from " << distance);
      MeshHit hit;
      REQUIRE(bvh.intersect(ray, 0.0f, hit, 2.0f) == (bestTriangle != kNoHit));
      if (bestTriangle != kNoHit) {
        REQUIRE(hit.t == bestT);
        ++farHits;
      }
    }
    CHECK(farHits > 20);
  }
}

TEST_CASE("A mesh gets float nodes up to floatNodesUpToTriangles triangles and byte nodes above") {
  const Mesh mesh = makeSphere(40, 20);  // its pole triangles are degenerate and do not count
  const MeshBvh counted(mesh, "sphere");
  const std::size_t triangles = counted.triangleCount();
  REQUIRE(triangles < mesh.triangleCount());
  CHECK_FALSE(counted.nodes().empty());  // the default keeps small meshes in float nodes
  BuildConfig config;
  config.floatNodesUpToTriangles = triangles;
  const MeshBvh atLimit(mesh, "sphere", config);
  CHECK_FALSE(atLimit.nodes().empty());
  CHECK(atLimit.quantizedNodes().empty());
  config.floatNodesUpToTriangles = triangles - 1;
  const MeshBvh overLimit(mesh, "sphere", config);
  CHECK(overLimit.nodes().empty());
  CHECK_FALSE(overLimit.quantizedNodes().empty());
}

TEST_CASE("The default node format follows the merged leaf size: larger leaves keep float nodes on more triangles") {
  // Between the two defaults: 16 * 32 768 < triangles <= 32 * 32 768.
  const Mesh mesh = makeSphere(730, 366);
  REQUIRE(mesh.triangleCount() <= floatNodesUpToTrianglesFor(32));
  BuildConfig config;
  config.mergedLeafSize = 16;
  const MeshBvh small(mesh, "sphere", config);
  REQUIRE(small.triangleCount() > floatNodesUpToTrianglesFor(16));
  CHECK(small.nodes().empty());
  CHECK_FALSE(small.quantizedNodes().empty());
  config.mergedLeafSize = 32;
  const MeshBvh large(mesh, "sphere", config);
  CHECK_FALSE(large.nodes().empty());
  CHECK(large.quantizedNodes().empty());
}

TEST_CASE("Wide child boxes enclose their leaves' triangles, in both node formats") {
  const Mesh mesh = makeSphere(60, 30);
  const bool quantized = GENERATE(false, true);
  INFO("quantized nodes: " << quantized);
  const MeshBvh bvh(mesh, "sphere", nodesQuantized(quantized, {16, 4, 2.0f}));
  REQUIRE(bvh.nodes().empty() == quantized);
  REQUIRE(bvh.quantizedNodes().empty() == !quantized);
  int leaves = 0;
  auto check = [&](const auto& nodes) {
    for (const auto& node : nodes) {
      for (int i = 0; i < kWidth; ++i) {
        if (node.count[i] == WideNode::kEmpty || node.count[i] == 0) continue;
        const Aabb box = node.childBox(i);
        for (std::uint32_t k = 0; k < node.count[i]; ++k) {
          const TrianglePositions t = bvh.slotTriangle(node.child[i] + k);
          for (const glm::vec3& p : {t.p0, t.p1, t.p2}) {
            REQUIRE(glm::all(glm::lessThanEqual(box.min, p)));
            REQUIRE(glm::all(glm::greaterThanEqual(box.max, p)));
          }
        }
        ++leaves;
      }
    }
  };
  check(bvh.nodes());
  check(bvh.quantizedNodes());
  CHECK(leaves > 100);
}

TEMPLATE_TEST_CASE("Batches touching more instances than the candidate list holds still match single queries", "", VT_KERNEL_LEVELS) {
  VT_USE_KERNEL_LEVEL();
  const bool inTurns = GENERATE(false, true);
  INFO("batches in turns: " << inTurns);
  // 40 overlapping copies of one mesh and 16 spheres among them: 640 sphere-instance pairs.
  auto scene = randomScene(3);
  const SceneObject first = scene->objects[0];
  scene->objects.clear();
  std::mt19937 rng(9);
  for (int i = 0; i < 40; ++i) {
    SceneObject o = first;
    o.T_world_object = glm::translate(glm::mat4(1.0f), randomVec(rng, -0.05f, 0.05f));
    scene->objects.push_back(o);
  }
  const CollisionScene world(scene, batchesInTurns(inTurns));
  std::vector<Sphere> spheres;
  for (int i = 0; i < 16; ++i) spheres.push_back({randomVec(rng, -0.5f, 0.5f), 1.5f});
  std::vector<SphereContact> batch(spheres.size());
  world.sphereContacts(spheres, batch);
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const SphereContact single = world.sphereContact(spheres[i]);
    REQUIRE(single.hit());
    CHECK(batch[i].object == single.object);
    CHECK(batch[i].triangle == single.triangle);
    CHECK(batch[i].distance_m == single.distance_m);
  }
  std::vector<Ray> rays;
  for (const Sphere& s : spheres) rays.push_back({s.center + glm::vec3(0.0f, 3.0f, 0.0f), {0.0f, -1.0f, 0.0f}});
  std::vector<RayHit> rayBatch(rays.size());
  world.intersect(rays, rayBatch);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const RayHit single = world.intersect(rays[i]);
    CHECK(rayBatch[i].object == single.object);
    CHECK(rayBatch[i].t == single.t);
  }
}
