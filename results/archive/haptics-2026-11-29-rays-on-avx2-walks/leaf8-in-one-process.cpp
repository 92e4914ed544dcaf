#include "haptics_workload.hpp"
#include "vt/collision/collision_scene.hpp"
#include "vt/collision/simd.hpp"
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <vector>
#include <cstdlib>
static double cpuSeconds() { timespec t; clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t); return t.tv_sec + t.tv_nsec * 1e-9; }
int main(int argc, char** argv) {
  using namespace vt;
  const int slices = argc > 1 ? std::atoi(argv[1]) : 1000;
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 21;
  const bool batch = argc > 3;
  auto scene = bench::bumpySphereScene(slices, slices / 2);
  const collision::CollisionScene world(scene);
  const auto rays = bench::makeRays(200000, 7);
  const auto spheres = bench::makeSpheres(200000, 9);
  const collision::SimdLevel levels[3] = {collision::SimdLevel::Avx512, collision::SimdLevel::Avx2, collision::SimdLevel::Avx512OnAvx2};
  std::vector<double> r[3], s[3];
  float sink = 0;
  std::vector<float> ans[3];
  for (int round = 0; round < rounds; ++round) {
    double tr[3], ts[3];
    for (int k = 0; k < 3; ++k) {
      const int side = (round + k) % 3;
      collision::setSimdLevel(levels[side]);
      double t0 = cpuSeconds();
      if (round == 0) ans[side].clear();
      for (const auto& q : rays) { float t = world.intersect(q).t; sink += t; if (round == 0) ans[side].push_back(t); }
      double t1 = cpuSeconds();
      if (batch) { collision::RayHit out[16]; for (std::size_t i = 0; i + 16 <= rays.size(); i += 16) { world.intersect(std::span(rays.data() + i, 16), std::span(out)); sink += out[3].t; } }
      else for (const auto& q : spheres) sink += world.sphereContact(q).depth_m;
      double t2 = cpuSeconds();
      tr[side] = t1 - t0, ts[side] = t2 - t1;
    }
    for (int k = 1; k < 3; ++k) { r[k].push_back(tr[0] / tr[k]); s[k].push_back(ts[0] / ts[k]); }
  }
  for (int k = 1; k < 3; ++k) { std::sort(r[k].begin(), r[k].end()); std::sort(s[k].begin(), s[k].end()); }
  std::printf("tri %zu: avx2/avx512 rays %.4f spheres %.4f | leaf8-vl/avx512 rays %.4f [%.3f..%.3f] second(%s) %.4f  same=%d\n",
    scene->meshes[0].triangleCount(), r[1][rounds/2], s[1][rounds/2], r[2][rounds/2], r[2][0], r[2][rounds-1], batch ? "batch16" : "spheres", s[2][rounds/2],
    int(ans[0]==ans[2] && ans[0]==ans[1]));
  return sink == 12345;
}
