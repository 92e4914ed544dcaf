#include <catch2/catch.hpp>

#include <limits>
#include <random>
#include <set>

#include "vt/collision/bvh.hpp"

using namespace vt;
using namespace vt::collision;

namespace {

// Every primitive in exactly one leaf, leaves no larger than maxLeaf, every node's box exactly
// the union of its children's or primitives' boxes, depth below the traversal stacks' 64.
void checkBvh(const std::vector<Aabb>& boxes, const Bvh& bvh, std::uint32_t maxLeaf) {
  std::multiset<std::uint32_t> seen;
  std::vector<std::pair<std::uint32_t, int>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [index, depth] = stack.back();
    stack.pop_back();
    REQUIRE(depth < 64);
    const BvhNode& node = bvh.nodes[index];
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    if (node.isLeaf()) {
      REQUIRE(node.count <= maxLeaf);
      for (std::uint32_t k = 0; k < node.count; ++k) {
        const std::uint32_t p = bvh.primIds[node.index + k];
        seen.insert(p);
        lo = glm::min(lo, boxes[p].min), hi = glm::max(hi, boxes[p].max);
      }
    } else {
      REQUIRE(node.index > index);
      for (std::uint32_t c : {node.index, node.index + 1}) {
        lo = glm::min(lo, bvh.nodes[c].min), hi = glm::max(hi, bvh.nodes[c].max);
        stack.push_back({c, depth + 1});
      }
    }
    REQUIRE(node.min == lo);
    REQUIRE(node.max == hi);
  }
  REQUIRE(seen.size() == boxes.size());
  REQUIRE(std::set<std::uint32_t>(seen.begin(), seen.end()).size() == boxes.size());
}

}  // namespace

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
    checkBvh(boxes, buildBvh(boxes, {16, 4, 1.0f}), 4);
  }
  CHECK(buildBvh({}).empty());
}

TEST_CASE("Ranges too large to bin whole bin a sample, and their nodes still hold their contents exactly") {
  // Ranges of more than 1024 boxes bin one in four: their children bin inside the box of the
  // samples, and each side's box is gathered while partitioning. Clustered and spread boxes.
  for (const std::size_t n : {1025u, 5000u, 40000u}) {
    std::mt19937 rng{std::uint32_t(n)};
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<Aabb> boxes(n);
    for (std::size_t i = 0; i < n; ++i) {
      const float spread = i % 7 == 0 ? 100.0f : 1.0f;  // a few far outliers the samples may miss
      const glm::vec3 c = spread * glm::vec3(u(rng), u(rng), u(rng));
      boxes[i] = {c - 0.01f * std::abs(u(rng)), c + 0.01f * std::abs(u(rng))};
    }
    INFO(n << " boxes");
    checkBvh(boxes, buildBvh(boxes, {16, 8, 2.0f, 4}), 8);
  }
}

TEST_CASE("The SAH builder handles identical, flat, point-sized and nearly coincident boxes") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const std::size_t n = 3000;  // large enough for the full bin count at the top, few bins below
  std::vector<std::vector<Aabb>> cases(5);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3 p(u(rng), u(rng), u(rng)), size(0.01f * (1.0f + u(rng)));
    cases[0].push_back({glm::vec3(0.5f), glm::vec3(0.75f)});                  // all identical
    cases[1].push_back({glm::vec3(p.x, p.y, 2.0f), glm::vec3(p.x, p.y, 2.0f) + glm::vec3(size.x, size.y, 0.0f)});  // flat in z
    cases[2].push_back({p, p});                                               // points
    cases[3].push_back({p * 1e-38f, p * 1e-38f});  // a range so small that bins per unit overflow
    cases[4].push_back({p * 1e-30f, p * 1e-30f + 1e-31f});                    // tiny but distinct extents
  }
  for (std::size_t c = 0; c < cases.size(); ++c) {
    INFO("case " << c);
    const Bvh bvh = buildBvh(cases[c], {16, 8, 2.0f});
    checkBvh(cases[c], bvh, 8);
    if (c == 1) CHECK(bvh.nodes.size() > n / 8);  // flat along z still splits along x and y
  }
}

TEST_CASE("Binning on box bounds splits a grid of squares between its squares") {
  // A 32 x 32 grid of unit squares: the best binary tree halves it cleanly, and binning on
  // box bounds must find those planes (a leaf per square pair or quad, no straddling leaves).
  std::vector<Aabb> boxes;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) boxes.push_back({glm::vec3(x, y, 0.0f), glm::vec3(x + 1, y + 1, 0.0f)});
  }
  const Bvh bvh = buildBvh(boxes, {16, 4, 1.0f});
  checkBvh(boxes, bvh, 4);
  for (const BvhNode& node : bvh.nodes) {
    if (!node.isLeaf()) continue;
    const glm::vec3 size = node.max - node.min;
    CHECK(size.x * size.y == Approx(float(node.count)));  // leaves tile the grid: no overlap
  }
}

TEST_CASE("Ranges of at most leafFloor primitives become leaves, larger ones are still split") {
  // A row of unit boxes: the SAH splits every range of two or more, so without a floor the
  // leaves are single boxes; with floor 4 no inner node holds 4 or fewer.
  std::vector<Aabb> boxes;
  for (int x = 0; x < 257; ++x) boxes.push_back({glm::vec3(2.0f * float(x), 0.0f, 0.0f), glm::vec3(2.0f * float(x) + 1.0f, 1.0f, 1.0f)});
  auto under = [](const Bvh& bvh, std::uint32_t node, auto&& self) -> std::uint32_t {
    const BvhNode& n = bvh.nodes[node];
    return n.isLeaf() ? n.count : self(bvh, n.index, self) + self(bvh, n.index + 1, self);
  };
  for (const int floor : {1, 4, 8}) {
    INFO("floor " << floor);
    const Bvh bvh = buildBvh(boxes, {16, 8, 1.0f, floor});
    checkBvh(boxes, bvh, 8);
    std::uint32_t smallestInner = 1u << 30, largestLeaf = 0;
    for (std::uint32_t i = 0; i < bvh.nodes.size(); ++i) {
      if (bvh.nodes[i].isLeaf()) {
        largestLeaf = std::max(largestLeaf, bvh.nodes[i].count);
      } else {
        smallestInner = std::min(smallestInner, under(bvh, i, under));
      }
    }
    CHECK(smallestInner > std::uint32_t(floor));
    if (floor == 1) CHECK(largestLeaf == 1);
    if (floor > 1) CHECK(largestLeaf > 1);
  }
  // A floor above maxLeafSize is capped at it: leaves never exceed maxLeafSize.
  checkBvh(boxes, buildBvh(boxes, {16, 2, 1.0f, 8}), 2);
}
