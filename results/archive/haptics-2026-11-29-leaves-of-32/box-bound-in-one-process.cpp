// New AVX2 kernels (level avx2) against HEAD's (compiled as avx512_on_avx2) on one tree in one
// process: single rays and single spheres, interleaved rounds, each side's timed pass after an
// untimed one, thread CPU time, medians of per-round ratios (> 1: new faster).
#include "haptics_workload.hpp"
#include "vt/collision/collision_scene.hpp"
#include "vt/collision/simd.hpp"
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>
static double cpuSeconds() { timespec t; clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t); return t.tv_sec + t.tv_nsec * 1e-9; }
int main(int argc, char** argv) {
  using namespace vt;
  const int merged = std::atoi(argv[1]);
  const int rounds = std::atoi(argv[2]);
  const int slices = argc > 3 ? std::atoi(argv[3]) : 1000;
  collision::BuildConfig config; config.mergedLeafSize = merged;
  auto scene = bench::bumpySphereScene(slices, slices / 2);
  const collision::CollisionScene world(scene, config);
  const auto rays = bench::makeRays(200000, 7);
  const auto spheres = bench::makeSpheres(200000, 9);
  const collision::SimdLevel levels[2] = {argc > 4 ? collision::SimdLevel::Avx512AllQueries : collision::SimdLevel::Avx2, collision::SimdLevel::Avx512OnAvx2};
  std::vector<double> rr, sr; std::vector<float> ans[2]; double sink = 0;
  for (int round = 0; round < rounds; ++round) {
    double t[2][2];
    for (int k = 0; k < 2; ++k) {
      const int side = (round + k) % 2;
      if (!collision::setSimdLevel(levels[side])) return 2;
      for (int pass = 0; pass < 2; ++pass) {
        ans[side].clear();
        const double t0 = cpuSeconds();
        for (const auto& r : rays) ans[side].push_back(world.intersect(r).t);
        const double t1 = cpuSeconds();
        for (const auto& s : spheres) ans[side].push_back(world.sphereContact(s).depth_m);
        const double t2 = cpuSeconds();
        t[side][0] = t1 - t0, t[side][1] = t2 - t1;
      }
    }
    rr.push_back(t[1][0] / t[0][0]); sr.push_back(t[1][1] / t[0][1]);
    for (float x : ans[0]) sink += x;
  }
  std::sort(rr.begin(), rr.end()); std::sort(sr.begin(), sr.end());
  std::printf("merged %d tri %zu: new/old rays %.3f [%.3f..%.3f] spheres %.3f [%.3f..%.3f] same=%d\n", merged, scene->meshes[0].triangleCount(),
              rr[rr.size()/2], rr.front(), rr.back(), sr[sr.size()/2], sr.front(), sr.back(), int(ans[0] == ans[1]));
  return sink == 1.2345;
}
