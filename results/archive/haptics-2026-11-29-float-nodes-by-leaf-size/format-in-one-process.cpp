// Scratch: float against byte nodes on the suite's 1M-triangle sphere in one process (the same
// code, only the format differs). Builds both scenes, then times single rays and spheres
// through CollisionScene in interleaved rounds (thread CPU time); prints medians of the
// per-round ratios. Build: see README.md in this folder.
#include "haptics_workload.hpp"
#include "vt/collision/collision_scene.hpp"
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <vector>
#include <cstdlib>
#include <string>
#include "vt/collision/simd.hpp"
static double cpuSeconds() { timespec t; clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t); return t.tv_sec + t.tv_nsec * 1e-9; }
// Arguments: [slices [avx2]]: the sphere's slices (stacks half as many); avx2: the AVX2 kernels
// and their 16-triangle merged leaves.
int main(int argc, char** argv) {
  using namespace vt;
  const int slices = argc > 1 ? std::atoi(argv[1]) : 1000;
  const bool avx2 = argc > 2 && std::string(argv[2]) == "avx2";
  auto scene = bench::bumpySphereScene(slices, slices / 2);
  collision::BuildConfig bytes, floats;
  if (avx2) {
    collision::setSimdLevel(collision::SimdLevel::Avx2);
    bytes.mergedLeafSize = floats.mergedLeafSize = 16;
  }
  bytes.floatNodesUpToTriangles = 0;
  floats.floatNodesUpToTriangles = SIZE_MAX;
  const collision::CollisionScene world[2] = {collision::CollisionScene(scene, bytes), collision::CollisionScene(scene, floats)};
  const auto rays = bench::makeRays(200000, 7);
  const auto spheres = bench::makeSpheres(200000, 9);
  std::vector<double> rayRatio, sphereRatio, buildRatio;
  float sink = 0;
  for (int round = 0; round < 21; ++round) {
    double t[2][2];
    for (int k = 0; k < 2; ++k) {
      const int side = round % 2 ? 1 - k : k;
      double t0 = cpuSeconds();
      for (const auto& r : rays) sink += world[side].intersect(r).t;
      double t1 = cpuSeconds();
      for (const auto& s : spheres) sink += world[side].sphereContact(s).depth_m;
      double t2 = cpuSeconds();
      t[side][0] = t1 - t0, t[side][1] = t2 - t1;
    }
    rayRatio.push_back(t[0][0] / t[1][0]);
    sphereRatio.push_back(t[0][1] / t[1][1]);
  }
  std::sort(rayRatio.begin(), rayRatio.end());
  std::sort(sphereRatio.begin(), sphereRatio.end());
  std::printf("{\"triangles\": %zu, \"kernels\": \"%s\", \"float_vs_bytes_rays\": %.4f, \"rays_min\": %.4f, \"rays_max\": %.4f, \"float_vs_bytes_spheres\": %.4f, \"spheres_min\": %.4f, \"spheres_max\": %.4f, \"rounds\": 21, \"sink\": %g}\n",
              scene->meshes[0].triangleCount(), collision::simdLevelName(collision::simdLevel()), rayRatio[10], rayRatio[0], rayRatio[20], sphereRatio[10], sphereRatio[0], sphereRatio[20], double(sink));
}
