#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <random>
#include <tuple>

#include "kernels.hpp"  // collision/src: the sets' internal child order
#include "random_scene.hpp"

// Not `using namespace vt::collision`: its kernel namespaces share the level types' names.
TEMPLATE_TEST_CASE("Every kernel level pushes a node's hit children farthest first", "", VT_KERNEL_LEVELS) {
  // The order only steers a walk, so no answer above would show a wrong one: checked here
  // against the documented rule. Hits first, by key with the lowest four bits of each key's bits
  // ignored (keys within 16 ulps may swap), ties by higher slot; then the misses, higher slot
  // first. Keys are >= 0 in use; ties and near-ties are common on purpose.
  VT_USE_KERNEL_LEVEL();
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> distance(0.0f, 50.0f);
  for (int round = 0; round < 200000; ++round) {
    float key[vt::collision::kWidth];
    for (float& k : key) {
      switch (rng() % 3) {
        case 0: k = distance(rng); break;
        case 1: k = float(rng() % 3); break;  // exact ties
        default: k = std::bit_cast<float>(0x3f800000u + std::uint32_t(rng() % 40)); break;  // ulps apart
      }
    }
    const unsigned mask = rng() & 0xffu;
    std::uint8_t slots[vt::collision::kWidth];
    vt::collision::activeKernels().orderChildren(key, mask, slots);
    std::uint8_t expected[vt::collision::kWidth];
    for (int i = 0; i < vt::collision::kWidth; ++i) expected[i] = std::uint8_t(i);
    auto rank = [&](int i) {
      std::uint32_t bits;
      std::memcpy(&bits, &key[i], sizeof bits);
      const bool hit = (mask >> i & 1u) != 0;
      return std::tuple(hit, hit ? bits >> 4 : 0u, i);
    };
    std::sort(expected, expected + vt::collision::kWidth, [&](int a, int b) { return rank(a) > rank(b); });
    INFO("round " << round << " mask " << mask);
    for (int j = 0; j < vt::collision::kWidth; ++j) REQUIRE(int(slots[j]) == int(expected[j]));
  }
}

TEST_CASE("On AVX-512 CPUs rays take the AVX2 walks and point queries the AVX-512 ones") {
#if defined(__x86_64__)
  namespace c = vt::collision;
  const vt::test::ScopedSimdLevel chosen(c::SimdLevel::Avx512);
  if (!chosen.active) VT_SKIP("this CPU cannot run the avx512 kernels");
  // Which walks a level runs shows in no answer (every set's are bit-identical): the tables.
  auto check = [](const auto& walks, const auto& rays, const auto& points) {
    CHECK(walks.intersect == rays.intersect);
    CHECK(walks.intersects == rays.intersects);
    CHECK(walks.closestPoint == points.closestPoint);
    CHECK(walks.closestPoints == points.closestPoints);
  };
  const c::QueryKernels& mixed = c::activeKernels();
  check(mixed.floatNodes, c::avx2::kKernels.floatNodes, c::avx512::kKernels.floatNodes);
  check(mixed.quantizedNodes, c::avx2::kKernels.quantizedNodes, c::avx512::kKernels.quantizedNodes);
  REQUIRE(c::setSimdLevel(c::SimdLevel::Avx512AllQueries));
  const c::QueryKernels& all = c::activeKernels();
  check(all.floatNodes, c::avx512::kKernels.floatNodes, c::avx512::kKernels.floatNodes);
  check(all.quantizedNodes, c::avx512::kKernels.quantizedNodes, c::avx512::kKernels.quantizedNodes);
#else
  VT_SKIP("not an x86-64 build: no AVX-512 kernels");
#endif
}
