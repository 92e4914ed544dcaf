// Trees of two merged leaf sizes and Embree in one process: single rays and spheres, rounds
// rotating the order, each side's timed pass after an untimed one, thread CPU time, medians.
#include "embree_side.hpp"
#include "haptics_workload.hpp"
#include "vt/collision/collision_scene.hpp"
#include "vt/collision/simd.hpp"
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <vector>
static double cpuSeconds() { timespec t; clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t); return t.tv_sec + t.tv_nsec * 1e-9; }
static double med(std::vector<double> v) { std::sort(v.begin(), v.end()); return v[v.size() / 2]; }
int main(int argc, char** argv) {
  using namespace vt;
  const int mA = std::atoi(argv[1]), mB = std::atoi(argv[2]);
  const int rounds = std::atoi(argv[3]);
  const std::string level = argv[4];
  const std::string isa = argv[5];  // "" for Embree's best kernels, or "avx2", "sse4.2"
  const int slices = argc > 6 ? std::atoi(argv[6]) : 1000;
  auto scene = bench::bumpySphereScene(slices, slices / 2);
  collision::BuildConfig ca, cb; ca.floatNodesUpToTriangles = std::size_t(mA) << 20; cb.floatNodesUpToTriangles = std::size_t(mB) << 20;
  auto a = std::make_unique<collision::CollisionScene>(scene, ca);
  auto b = std::make_unique<collision::CollisionScene>(scene, cb);
  bench::EmbreeMesh embree(scene->meshes[0], RTC_BUILD_QUALITY_MEDIUM, isa);
  embree.build();
  for (auto l : collision::kSimdLevels) if (level == collision::simdLevelName(l)) collision::setSimdLevel(l);
  const auto rays = bench::makeRays(200000, 7);
  const auto spheres = bench::makeSpheres(200000, 9);
  std::vector<double> ra, rb, sa, sb, rab, sab; double sink = 0;
  for (int round = 0; round < rounds; ++round) {
    double t[3][2];
    for (int k = 0; k < 3; ++k) {
      const int side = (round + k) % 3;
      for (int pass = 0; pass < 2; ++pass) {
        const double t0 = cpuSeconds();
        if (side == 2) for (const auto& r : rays) sink += embree.intersect(r);
        else { const auto& w = side == 0 ? *a : *b; for (const auto& r : rays) sink += w.intersect(r).t; }
        const double t1 = cpuSeconds();
        if (side == 2) for (const auto& s : spheres) sink += embree.closestDistance(s);
        else { const auto& w = side == 0 ? *a : *b; for (const auto& s : spheres) sink += w.sphereContact(s).depth_m; }
        const double t2 = cpuSeconds();
        t[side][0] = t1 - t0, t[side][1] = t2 - t1;
      }
    }
    ra.push_back(t[2][0] / t[0][0]); rb.push_back(t[2][0] / t[1][0]);
    sa.push_back(t[2][1] / t[0][1]); sb.push_back(t[2][1] / t[1][1]);
    rab.push_back(t[0][0] / t[1][0]); sab.push_back(t[0][1] / t[1][1]);
  }
  std::printf("threads=1,hugepages=1%s tri %d level %s | rays vs embree: m%d %.3f m%d %.3f (m%d/m%d %.3f) | spheres: m%d %.3f m%d %.3f (%.3f)\n", isa.empty() ? "" : (",isa=" + isa).c_str(), slices * slices,
              level.c_str(), mA, med(ra), mB, med(rb), mB, mA, med(rab), mA, med(sa), mB, med(sb), med(sab));
  return sink == 1.2345;
}
