// The kernel levels on one tree in one process (the same build of the library): the default
// `avx512` (AVX2 ray walks, AVX-512 point walks) against `avx512-all-queries` (AVX-512 walks for
// rays too) and `avx2`. Single rays, 16-ray batches and single spheres on the suite's bumpy
// sphere; thread CPU time, interleaved rounds (the order rotating), medians of per-round ratios.
// Arguments: [slices [rounds]].
#include "haptics_workload.hpp"
#include "vt/collision/collision_scene.hpp"
#include "vt/collision/simd.hpp"
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <span>
#include <vector>
static double cpuSeconds() { timespec t; clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t); return t.tv_sec + t.tv_nsec * 1e-9; }
int main(int argc, char** argv) {
  using namespace vt;
  const int slices = argc > 1 ? std::atoi(argv[1]) : 1000;
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 21;
  auto scene = bench::bumpySphereScene(slices, slices / 2);
  const collision::CollisionScene world(scene);
  const auto rays = bench::makeRays(200000, 7);
  const auto spheres = bench::makeSpheres(200000, 9);
  using L = collision::SimdLevel;
  const L levels[3] = {L::Avx512, L::Avx512AllQueries, L::Avx2};
  std::vector<double> ratio[3][3];  // [level 1, 2 over level 0][rays, batches, spheres]
  std::vector<float> answers[3];
  float sink = 0;
  for (int round = 0; round < rounds; ++round) {
    double t[3][3];
    for (int k = 0; k < 3; ++k) {
      const int side = (round + k) % 3;
      if (!collision::setSimdLevel(levels[side])) return 2;
      answers[side].clear();
      const double t0 = cpuSeconds();
      for (const auto& r : rays) answers[side].push_back(world.intersect(r).t);
      const double t1 = cpuSeconds();
      collision::RayHit out[16];
      for (std::size_t i = 0; i + 16 <= rays.size(); i += 16) {
        world.intersect(std::span(rays.data() + i, 16), std::span(out));
        sink += out[5].t;
      }
      const double t2 = cpuSeconds();
      for (const auto& s : spheres) sink += world.sphereContact(s).depth_m;
      const double t3 = cpuSeconds();
      t[side][0] = t1 - t0, t[side][1] = t2 - t1, t[side][2] = t3 - t2;
    }
    for (int side = 1; side < 3; ++side)
      for (int q = 0; q < 3; ++q) ratio[side][q].push_back(t[side][q] / t[0][q]);  // > 1: the default is faster
  }
  auto median = [&](std::vector<double> v) { std::sort(v.begin(), v.end()); return v[v.size() / 2]; };
  std::printf("{\"triangles\": %zu, \"rounds\": %d, \"same_answers\": %s,\n", scene->meshes[0].triangleCount(), rounds,
              answers[0] == answers[1] && answers[0] == answers[2] ? "true" : "false");
  const char* names[3] = {"", "avx512_all_queries", "avx2"};
  for (int side = 1; side < 3; ++side)
    std::printf(" \"default_vs_%s\": {\"rays\": %.4f, \"rays_min\": %.4f, \"rays_max\": %.4f, \"batch16\": %.4f, \"spheres\": %.4f}%s\n",
                names[side], median(ratio[side][0]), *std::min_element(ratio[side][0].begin(), ratio[side][0].end()),
                *std::max_element(ratio[side][0].begin(), ratio[side][0].end()), median(ratio[side][1]),
                median(ratio[side][2]), side == 1 ? "," : "");
  std::printf(" \"sink\": %g}\n", double(sink));
}
