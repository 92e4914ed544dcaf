// Two revisions of the collision library in one process (scripts/collision-ab.sh builds it):
// the haptics suite's scene and queries (bench/haptics_workload.hpp) answered by side A and
// side B in alternating passes, A first in even rounds and B first in odd ones. Separate
// processes differ by several percent on this kind of machine (page placement, neighbours'
// load); passes alternating within one process share all of that, so small changes show.
//   ab --kind rays|batch16|spheres|spheres12|build [--slices N] [--queries N] [--rounds N]
//      [--only a|b|embree --passes N]    one side alone (or Embree 3, as vt_bench haptics
//                                         times it), for counting under valgrind
// build: each pass frees the side's CollisionScene and builds it anew, the build alone timed
// (as vt_bench haptics times builds); the answers checked are the rays' of the last builds.
// Prints one JSON object: each side's median rate (build: milliseconds a build), the median
// and range of the per-round ratios B / A (speed), how many answers differ (exit 1 when any
// does), the machine and the load averages before and after.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ab.hpp"
#include "embree_side.hpp"
#include "haptics_workload.hpp"
#include "interleaved_runs.hpp"
#include "results_file.hpp"

namespace {

[[noreturn]] void usage(const char* why) {
  std::fprintf(stderr,
               "ab: %s\nusage: ab --kind rays|batch16|spheres|spheres12|build [--slices N] [--queries N] [--rounds N] "
               "[--only a|b|embree --passes N]\n",
               why);
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  std::string kindName = "rays", only;
  int slices = 1000, rounds = 15, passes = 1;
  std::size_t queries = 200'000;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(("missing value after " + arg).c_str());
      return argv[++i];
    };
    if (arg == "--kind") kindName = value();
    else if (arg == "--slices") slices = std::atoi(value().c_str());
    else if (arg == "--queries") queries = std::size_t(std::atol(value().c_str()));
    else if (arg == "--rounds") rounds = std::atoi(value().c_str());
    else if (arg == "--only") only = value();
    else if (arg == "--passes") passes = std::atoi(value().c_str());
    else usage(("unknown argument " + arg).c_str());
  }
  if (slices < 4 || queries == 0 || rounds < 1 || passes < 0) usage("slices >= 4, queries >= 1, rounds >= 1, passes >= 0");
  if (!only.empty() && only != "a" && only != "b" && only != "embree") usage("--only takes a, b or embree");

  ab::Workload work;
  if (kindName == "rays") work.kind = ab::Kind::Rays;
  else if (kindName == "batch16") work.kind = ab::Kind::RayBatches;
  else if (kindName == "spheres") work.kind = ab::Kind::Spheres;
  else if (kindName == "spheres12") work.kind = ab::Kind::SphereBatches;
  else if (kindName == "build") work.kind = ab::Kind::Build;
  else usage(("unknown kind " + kindName).c_str());
  const auto scene = vt::bench::bumpySphereScene(slices, slices / 2);
  for (const vt::Vertex& v : scene->meshes[0].vertices) work.positions.push_back(v.position);
  work.indices = scene->meshes[0].indices;
  // The suite's seeds: rays 1, spheres 2.
  const bool spheres = work.kind == ab::Kind::Spheres || work.kind == ab::Kind::SphereBatches;
  if (spheres) {
    for (const auto& s : vt::bench::makeSpheres(queries, 2)) work.origins.push_back(s.center), work.radius = s.radius_m;
  } else {
    for (const auto& r : vt::bench::makeRays(queries, 1)) work.origins.push_back(r.origin), work.directions.push_back(r.direction);
  }
  std::vector<float> answersA(queries), answersB(queries);

  if (only == "embree") {  // the suite's comparison point, default build quality
    if (work.kind == ab::Kind::Build) {  // counts include making the device and buffers, which the suite leaves out of its timing
      for (int p = 0; p < passes; ++p) vt::bench::EmbreeMesh(scene->meshes[0], RTC_BUILD_QUALITY_MEDIUM).build();
      return 0;
    }
    vt::bench::EmbreeMesh embree(scene->meshes[0], RTC_BUILD_QUALITY_MEDIUM);
    embree.build();
    for (int p = 0; p < passes; ++p) {
      for (std::size_t i = 0; i < queries; ++i) {
        if (spheres) {
          answersA[i] = embree.closestDistance({work.origins[i], work.radius});
        } else {
          vt::collision::Ray ray;
          ray.origin = work.origins[i];
          ray.direction = work.directions[i];
          answersA[i] = embree.intersect(ray);
        }
      }
    }
    return 0;
  }
  if (!only.empty()) {  // one side, `passes` times (valgrind: the difference of two pass counts is one pass)
    const auto world = only == "a" ? makeWorldA(work) : makeWorldB(work);
    world->rebuild();
    for (int p = 0; p < passes; ++p) {
      if (work.kind == ab::Kind::Build) world->rebuild();
      else world->answer(work, answersA.data());
    }
    return 0;
  }

  const auto loadBefore = vt::bench::loadAverage();
  const auto a = makeWorldA(work);
  const auto b = makeWorldB(work);
  a->rebuild();
  b->rebuild();
  const bool build = work.kind == ab::Kind::Build;
  auto side = [&](const char* name, ab::World& world, std::vector<float>& answers) {
    if (build) return vt::bench::Side{name, 1, {}, [&world] { return world.rebuild(); }};
    return vt::bench::Side{name, queries, [&] { world.answer(work, answers.data()); }};
  };
  vt::bench::Side sideA = side("a", *a, answersA);
  vt::bench::Side sideB = side("b", *b, answersB);
  vt::bench::runInterleaved({&sideA, &sideB}, rounds);
  if (build) {  // the trees of the last builds answer the rays
    a->answer(work, answersA.data());
    b->answer(work, answersB.data());
  }
  std::size_t differing = 0;
  for (std::size_t i = 0; i < queries; ++i) differing += std::memcmp(&answersA[i], &answersB[i], sizeof(float)) != 0;
  std::vector<double> ratios;  // B's speed over A's, per round
  for (int r = 0; r < rounds; ++r) ratios.push_back(sideA.seconds[std::size_t(r)] / sideB.seconds[std::size_t(r)]);
  nlohmann::ordered_json out;
  out["kind"] = kindName;
  out["triangles"] = work.indices.size() / 3;
  out["queries"] = queries;
  out["rounds"] = rounds;
  out["timing"] = "thread CPU time, interleaved rounds";
  if (build) {
    out["a_build_ms"] = sideA.medianMilliseconds();
    out["b_build_ms"] = sideB.medianMilliseconds();
  } else {
    out["a_mqueries_per_s"] = sideA.medianMillionsPerSecond();
    out["b_mqueries_per_s"] = sideB.medianMillionsPerSecond();
  }
  out["b_speed_vs_a"] = vt::bench::medianSpeedup(sideB, sideA);
  out["b_speed_vs_a_min"] = *std::min_element(ratios.begin(), ratios.end());
  out["b_speed_vs_a_max"] = *std::max_element(ratios.begin(), ratios.end());
  out["differing_answers"] = differing;
  out["load_before"] = loadBefore;
  out["load_after"] = vt::bench::loadAverage();
  out["machine"] = vt::bench::machineInfo();
  std::printf("%s\n", out.dump().c_str());
  return differing == 0 ? 0 : 1;
}
