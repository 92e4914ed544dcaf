#include <catch2/catch.hpp>

#include <random>
#include <set>

#include "vt/collision/bvh.hpp"

using namespace vt;
using namespace vt::collision;

TEST_CASE("The SAH builder keeps every primitive once and nodes enclose their contents") {
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-10.0f, 10.0f);
    const std::size_t n = 1 + seed * 37;
    std::vector<Aabb> boxes(n);
    for (std::size_t i = 0; i < n; ++i) {
      // Every 5th primitive shares one centre: the builder must still terminate and stay shallow.
      const glm::vec3 c = i % 5 == 0 ? glm::vec3(1.0f) : glm::vec3(u(rng), u(rng), u(rng));
      boxes[i] = {c - 0.1f, c + 0.2f};
    }
    const Bvh bvh = buildBvh(boxes, {16, 4, 1.0f});
    std::multiset<std::uint32_t> seen;
    std::vector<std::pair<std::uint32_t, int>> stack{{0, 0}};
    while (!stack.empty()) {
      const auto [index, depth] = stack.back();
      stack.pop_back();
      REQUIRE(depth < 64);
      const BvhNode& node = bvh.nodes[index];
      if (node.isLeaf()) {
        REQUIRE(node.count <= 4);
        for (std::uint32_t k = 0; k < node.count; ++k) {
          const std::uint32_t p = bvh.primIds[node.index + k];
          seen.insert(p);
          REQUIRE(glm::all(glm::lessThanEqual(node.min, boxes[p].min)));
          REQUIRE(glm::all(glm::greaterThanEqual(node.max, boxes[p].max)));
        }
        continue;
      }
      REQUIRE(node.index > index);
      for (std::uint32_t c : {node.index, node.index + 1}) {
        REQUIRE(glm::all(glm::lessThanEqual(node.min, bvh.nodes[c].min)));
        REQUIRE(glm::all(glm::greaterThanEqual(node.max, bvh.nodes[c].max)));
        stack.push_back({c, depth + 1});
      }
    }
    REQUIRE(seen.size() == n);
    REQUIRE(std::set<std::uint32_t>(seen.begin(), seen.end()).size() == n);
  }
  CHECK(buildBvh({}).empty());
}
