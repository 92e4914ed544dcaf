#include "haptics_workload.hpp"
#include "vt/collision/mesh_bvh.hpp"
#include <chrono>
#include <cstdio>
#include <algorithm>
#include <vector>
int main() {
  auto scene = vt::bench::bumpySphereScene(1000, 500);
  std::vector<double> t[2];
  for (int r = 0; r < 31; ++r) {
    for (int k = 0; k < 2; ++k) {
      int side = (r % 2) ? 1 - k : k;
      vt::collision::BuildConfig c; c.floatNodesUpToTriangles = side ? SIZE_MAX : 0;
      auto t0 = std::chrono::steady_clock::now();
      { vt::collision::MeshBvh b(scene->meshes[0], "s", c); }
      t[side].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
  }
  std::vector<double> ratio;
  for (std::size_t i = 0; i < t[0].size(); ++i) ratio.push_back(t[0][i] / t[1][i]);
  for (auto* v : {&t[0], &t[1], &ratio}) std::sort(v->begin(), v->end());
  std::printf("bytes median %.1f ms, float median %.1f ms, speed float/bytes median ratio %.3f\n", t[0][15], t[1][15], ratio[15]);
}
