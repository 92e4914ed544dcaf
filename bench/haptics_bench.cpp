// vt_bench haptics [--json] [--quick]: BVH build, ray and sphere query throughput against
// brute force and Embree 3 (default and high build quality) on the same scene and queries, with
// every query's answer checked against Embree's (exit 1 when they differ), haptic tick timing
// at 1 and 4 kHz and loop period jitter. Figures are quoted in docs/PERFORMANCE.md.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <span>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench.hpp"
#include "embree_side.hpp"
#include "haptics_workload.hpp"
#include "interleaved_runs.hpp"
#include "vt/collision/collision_scene.hpp"
#include "vt/collision/simd.hpp"
#include "vt/core/realtime.hpp"
#include "vt/haptics/haptic_loop.hpp"
#include "vt/scene/demo_scene.hpp"

namespace {

using namespace vt;
using bench::bumpySphereScene;
using bench::makeRays;
using bench::makeSpheres;
using bench::threadCpuSeconds;
using WallClock = std::chrono::steady_clock;

double bruteRayRate(const Scene& scene, const std::vector<collision::Ray>& rays) {
  const Mesh& mesh = scene.meshes[0];
  std::vector<glm::vec3> p;
  for (std::uint32_t i : mesh.indices) p.push_back(mesh.vertices[i].position);
  const double t0 = threadCpuSeconds();
  std::size_t hits = 0;
  for (const auto& r : rays) {
    const collision::PreparedRay pr(r.origin, r.direction);
    float best = r.tMax, t, u, v;
    bool hit = false;
    for (std::size_t k = 0; k + 2 < p.size(); k += 3) {
      if (collision::intersectTriangle(pr, p[k], p[k + 1], p[k + 2], r.tMin, best, t, u, v)) best = t, hit = true;
    }
    hits += hit;
  }
  benchmark::DoNotOptimize(hits);
  return double(rays.size()) / (threadCpuSeconds() - t0) / 1e6;
}

// Per-tick timing over every tick of a run (not the loop's recent-tick window).
struct TickTiming {
  std::size_t ticks = 0;
  double p50_us = 0.0, p99_us = 0.0, max_us = 0.0;  // wall time of each tickOnce()
  double cpuP50_us = 0.0, cpuP99_us = 0.0;           // its thread CPU time: preemption excluded
};

double percentile(const std::vector<double>& sorted, double q) {
  return sorted[std::min(sorted.size() - 1, std::size_t(q * double(sorted.size())))];
}

// Ticks `config`'s loop on the calling thread at its rate, paced by the wall clock (tick i
// starts at i periods, stamped i periods), over hands sliding on the surface at 1 m/s:
// poseAt(pose, a) places the joints at angle a (radians on the unit sphere) for the tick's time.
template <class PoseAt>
TickTiming tickTiming(std::shared_ptr<Scene> scene, haptics::HapticConfig config, int ticks, PoseAt&& poseAt) {
  auto history = std::make_unique<PoseHistory>();
  PoseHistory& poses = *history;
  config.sampling.timeout_ns = 0;
  config.tactile.model = haptics::TactileModelKind::TextureWaveform;
  haptics::HapticLoop loop(config, poses);
  loop.publishScene(haptics::makeHapticScene(std::move(scene)));
  const auto period_ns = std::int64_t(std::llround(1e9 / double(config.rate_hz)));
  std::vector<double> wall_us, cpu_us;
  wall_us.reserve(std::size_t(ticks));
  cpu_us.reserve(std::size_t(ticks));
  const WallClock::time_point start = WallClock::now();
  for (int i = 0; i < ticks; ++i) {
    HandPose pose;
    pose.valid = true;
    for (auto& r : pose.radius_m) r = kDefaultFingertipRadius_m;
    pose.t_ns = std::int64_t(i) * period_ns;
    poseAt(pose, float(double(pose.t_ns) * 1e-9));
    poses.publish(pose);
    std::this_thread::sleep_until(start + std::chrono::nanoseconds(pose.t_ns));
    const WallClock::time_point w0 = WallClock::now();
    const double t0 = threadCpuSeconds();
    loop.tickOnce(pose.t_ns);
    cpu_us.push_back((threadCpuSeconds() - t0) * 1e6);
    wall_us.push_back(std::chrono::duration<double, std::micro>(WallClock::now() - w0).count());
  }
  std::sort(wall_us.begin(), wall_us.end());
  std::sort(cpu_us.begin(), cpu_us.end());
  return {wall_us.size(), percentile(wall_us, 0.5), percentile(wall_us, 0.99), wall_us.back(),
          percentile(cpu_us, 0.5), percentile(cpu_us, 0.99)};
}

// A point just inside the unit sphere's surface at longitude a, latitude from y.
glm::vec3 onSurface(float a, float y) { return glm::normalize(glm::vec3(std::cos(a), y, std::sin(a))) * 1.005f; }

// Five fingertips in a row (the default single-hand configuration).
void fiveFingertipPose(HandPose& pose, float a) {
  for (int f = 0; f < kFingerCount; ++f) {
    pose.position[std::size_t(kFingertips[std::size_t(f)])] = onSurface(a + 0.05f * float(f), 0.3f);
  }
}

// Two hands, 12 contact points at 4 kHz: each hand's five fingertips and its palm (2 cm
// sphere). A HandPose holds one hand, so the second hand's points ride on joints the first
// leaves unused (the distal joints and the wrist), placed on the far side of the object:
// the collision and rendering work per tick is that of two hands.
haptics::HapticConfig twoHandsConfig() {
  haptics::HapticConfig config;
  config.rate_hz = 4000.0f;
  std::vector<HandJoint> joints(kFingertips.begin(), kFingertips.end());
  joints.push_back(HandJoint::Palm);
  for (HandJoint j : {HandJoint::ThumbDistal, HandJoint::IndexDistal, HandJoint::MiddleDistal, HandJoint::RingDistal,
                      HandJoint::LittleDistal, HandJoint::Wrist}) {
    joints.push_back(j);
  }
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const bool palm = joints[i] == HandJoint::Palm || joints[i] == HandJoint::Wrist;
    config.contacts.push_back({joints[i], palm ? 0.02f : 0.0f});
    config.routes.push_back({int(i), haptics::ActuatorId(i % std::size_t(haptics::kMaxActuators))});
  }
  return config;
}

void twoHandsPose(HandPose& pose, float a) {
  const auto at = [&](HandJoint j) -> glm::vec3& { return pose.position[std::size_t(j)]; };
  const HandJoint second[] = {HandJoint::ThumbDistal, HandJoint::IndexDistal, HandJoint::MiddleDistal,
                              HandJoint::RingDistal, HandJoint::LittleDistal};
  for (int f = 0; f < kFingerCount; ++f) {
    at(kFingertips[std::size_t(f)]) = onSurface(a + 0.05f * float(f), 0.3f);
    at(second[f]) = onSurface(a + 3.14159f + 0.05f * float(f), -0.3f);
  }
  at(HandJoint::Palm) = onSurface(a + 0.1f, 0.1f);
  at(HandJoint::Wrist) = onSurface(a + 3.14159f + 0.1f, -0.1f);
}

// Runs `config`'s loop on its own thread (HapticLoop::start, as the app does) for `seconds`.
// With `poseAt`, this thread publishes the hand every millisecond (a tracker's rate), stamped on
// the loop's clock and sliding at 1 m/s as in tickTiming; without, the loop ticks with no hand.
haptics::LoopStats loopRun(std::shared_ptr<Scene> scene, haptics::HapticConfig config, double seconds,
                           const std::function<void(HandPose&, float)>& poseAt = {}) {
  auto history = std::make_unique<PoseHistory>();
  PoseHistory& poses = *history;
  if (poseAt) config.tactile.model = haptics::TactileModelKind::TextureWaveform;
  haptics::HapticLoop loop(config, poses);
  SpscRing<haptics::ActuatorFrame> ring(8192);
  loop.addOutput(ring);
  loop.publishScene(haptics::makeHapticScene(std::move(scene)));
  const SteadyClock& clock = SteadyClock::instance();
  const std::int64_t start_ns = clock.now_ns(), end_ns = start_ns + std::int64_t(seconds * 1e9);
  loop.start();
  for (std::int64_t t_ns = start_ns; t_ns < end_ns; t_ns += 1'000'000) {
    if (poseAt) {
      HandPose pose;
      pose.valid = true;
      for (auto& r : pose.radius_m) r = kDefaultFingertipRadius_m;
      pose.t_ns = clock.now_ns();
      poseAt(pose, float(double(pose.t_ns - start_ns) * 1e-9));
      poses.publish(pose);
    }
    clock.sleepUntil(t_ns + 1'000'000);
  }
  loop.stop();
  return loop.stats();
}

// Ticks paced at their rate on the 1M-triangle scene: five fingertips at 1 kHz, two hands at
// 4 kHz (stamps 250 us apart); percentiles over every tick.
void tickFigures(const std::shared_ptr<Scene>& scene, bool quick, nlohmann::json& out) {
  const TickTiming ticks =
      tickTiming(scene, haptics::HapticConfig::fiveFingertips(), quick ? 1000 : 5000, fiveFingertipPose);
  out["tick_count"] = ticks.ticks;
  out["tick_p50_us"] = ticks.p50_us;
  out["tick_p99_us"] = ticks.p99_us;
  out["tick_max_us"] = ticks.max_us;
  out["tick_cpu_p99_us"] = ticks.cpuP99_us;
  const TickTiming twoHands = tickTiming(scene, twoHandsConfig(), quick ? 2000 : 20000, twoHandsPose);
  out["two_hands_4khz_tick_count"] = twoHands.ticks;
  out["two_hands_4khz_tick_p50_us"] = twoHands.p50_us;
  out["two_hands_4khz_tick_p99_us"] = twoHands.p99_us;
  out["two_hands_4khz_tick_max_us"] = twoHands.max_us;
  out["two_hands_4khz_tick_cpu_p50_us"] = twoHands.cpuP50_us;
  out["two_hands_4khz_tick_cpu_p99_us"] = twoHands.cpuP99_us;
  // The same two hands on the loop's own thread (HapticLoop::run), sleeping between ticks (the
  // default) and spinning (HapticConfig::pacing): runs of each, interleaved (the order reversed
  // every other round); per pacing the medians of the runs' p50 and p99 over every tick, the
  // longest tick, and the ticks and overruns summed.
  const int rounds = quick ? 1 : 5;
  const double seconds = quick ? 0.5 : 2.0;
  constexpr haptics::LoopPacing kPacings[] = {haptics::LoopPacing::Sleep, haptics::LoopPacing::Spin};
  std::vector<haptics::LoopStats> runs[2];
  for (int round = 0; round < rounds; ++round) {
    for (int k = 0; k < 2; ++k) {
      const int side = round % 2 == 0 ? k : 1 - k;
      haptics::HapticConfig config = twoHandsConfig();
      config.pacing = kPacings[side];
      runs[side].push_back(loopRun(scene, config, seconds, twoHandsPose));
    }
  }
  for (int side = 0; side < 2; ++side) {
    std::vector<double> p50, p99;
    double max_us = 0.0;
    std::uint64_t tickCount = 0, overruns = 0, stale = 0;
    for (const haptics::LoopStats& run : runs[side]) {
      p50.push_back(run.runTickP50_us);
      p99.push_back(run.runTickP99_us);
      max_us = std::max(max_us, run.runTickMax_us);
      tickCount += run.ticks;
      overruns += run.overruns;
      stale += run.stalePoses;
    }
    const std::string key = std::string("two_hands_4khz_loop_") + haptics::loopPacingName(kPacings[side]);
    out[key + "_runs"] = runs[side].size();
    out[key + "_ticks"] = tickCount;
    out[key + "_tick_p50_us"] = bench::median(p50);
    out[key + "_tick_p99_us"] = bench::median(p99);
    out[key + "_tick_p99_runs_us"] = p99;
    out[key + "_tick_max_us"] = max_us;
    out[key + "_overruns"] = overruns;
    out[key + "_stale_poses"] = stale;
  }
}

void printFigures(const nlohmann::json& out, bool json) {
  if (json) {
    std::printf("%s\n", out.dump().c_str());
  } else {
    for (const auto& [key, value] : out.items()) std::printf("%-32s %s\n", key.c_str(), value.dump().c_str());
  }
}

}  // namespace

namespace {

// Each timed figure is the median of this many interleaved runs (interleaved_runs.hpp).
constexpr int kRuns = 5;

// Set (to anything) by the test that a broken comparison fails the bench: our first ray hit
// is dropped before the answers are compared.
constexpr const char* kBreakHitsVariable = "VT_BENCH_BREAK_HITS";

// Our query answers as distances (kNone: nothing found), comparable with EmbreeMesh's.
float distanceOf(const collision::RayHit& h) { return h.hit() ? h.t : bench::kNone; }
float distanceOf(const collision::SphereContact& c) { return c.hit() ? c.distance_m : bench::kNone; }

// Our answers to `queries`, kBatch per call of `ask(queries, results)` (CollisionScene's
// span overloads).
template <std::size_t kBatch, class Result, class Query, class Ask>
void answerInBatches(const std::vector<Query>& queries, std::vector<float>& answers, Ask&& ask) {
  Result results[kBatch];
  for (std::size_t i = 0; i < queries.size(); i += kBatch) {
    const std::size_t count = std::min(kBatch, queries.size() - i);
    ask(std::span<const Query>(queries.data() + i, count), std::span<Result>(results, count));
    for (std::size_t k = 0; k < count; ++k) answers[i + k] = distanceOf(results[k]);
  }
}

std::size_t found(const std::vector<float>& answers) {
  return std::size_t(std::count_if(answers.begin(), answers.end(), [](float d) { return d != bench::kNone; }));
}

// The exact nearest hit distance of a ray (double precision over every triangle the BVH
// keeps; Moller-Trumbore), or kNone: the referee where our answer and Embree's differ.
float exactNearestHit(const Mesh& mesh, const collision::Ray& r) {
  const glm::dvec3 o(r.origin), d(r.direction);
  double best = double(r.tMax);
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const glm::vec3 a = mesh.vertices[mesh.indices[i]].position, b = mesh.vertices[mesh.indices[i + 1]].position,
                    c = mesh.vertices[mesh.indices[i + 2]].position;
    if (collision::isDegenerate(a, b, c)) continue;
    const glm::dvec3 p0(a), e1 = glm::dvec3(b) - p0, e2 = glm::dvec3(c) - p0;
    const glm::dvec3 h = glm::cross(d, e2);
    const double det = glm::dot(e1, h);
    if (det == 0.0) continue;
    const glm::dvec3 s = o - p0, q = glm::cross(s, e1);
    const double u = glm::dot(s, h) / det, v = glm::dot(d, q) / det, t = glm::dot(e2, q) / det;
    if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > double(r.tMin) && t < best) best = t;
  }
  return best < double(r.tMax) ? float(best) : bench::kNone;
}

// Our answers against Embree's, query by query (distances within kTolerance pass). Where a
// ray's answers differ, the exact answer decides: when it is ours, Embree missed the nearest
// surface (its triangle test is not watertight: rays through shared edges can fall through)
// and it is counted; any other difference is an error. Differences are printed to stderr.
struct HitCheck {
  static constexpr float kTolerance = 1e-4f;
  static constexpr std::size_t kMostRefereed = 1000;  // each exact answer tests every triangle
  std::size_t checked = 0, embreeMissed = 0, errors = 0;

  void rays(const Mesh& mesh, const std::vector<collision::Ray>& queries, const char* what,
            const std::vector<float>& ours, const std::vector<float>& theirs) {
    checked += ours.size();
    const std::vector<std::size_t> differ = bench::differingAnswers(ours, theirs, kTolerance);
    if (differ.size() > kMostRefereed) {  // not edge cases: no need to referee them all
      std::fprintf(stderr, "  %s: %zu rays differ\n", what, differ.size());
      errors += differ.size();
      return;
    }
    for (const std::size_t i : differ) {
      const float exact = exactNearestHit(mesh, queries[i]);
      const bool oursRight = bench::differingAnswers({ours[i]}, {exact}, kTolerance).empty();
      std::fprintf(stderr, "  %s: ray %zu: ours %.9g, embree %.9g, exact %.9g%s\n", what, i, double(ours[i]),
                   double(theirs[i]), double(exact), oursRight ? " (embree missed the nearest surface)" : "");
      ++(oursRight ? embreeMissed : errors);
    }
  }
  void spheres(const char* what, const std::vector<float>& ours, const std::vector<float>& theirs) {
    checked += ours.size();
    for (const std::size_t i : bench::differingAnswers(ours, theirs, kTolerance)) {
      std::fprintf(stderr, "  %s: sphere %zu: ours %.9g, embree %.9g\n", what, i, double(ours[i]), double(theirs[i]));
      ++errors;
    }
  }
};

}  // namespace

VT_BENCH_SUITE(haptics, "BVH build, ray/sphere queries (vs brute force and Embree), haptic tick") {
  const int slices = options.quick ? 100 : 1000, stacks = options.quick ? 50 : 500;
  const std::size_t queryCount = options.quick ? 20'000 : 500'000;
  nlohmann::json out;
  using bench::Side;

  auto scene = bumpySphereScene(slices, stacks);
  const Mesh& mesh = scene->meshes[0];
  out["triangles"] = mesh.triangleCount();
  out["runs"] = kRuns;

  // Builds: all of CollisionScene(scene) against rtcCommitScene alone (device, geometry and
  // buffers are made before the clock starts), default and high (SBVH) quality.
  std::unique_ptr<collision::CollisionScene> world;
  std::unique_ptr<bench::EmbreeMesh> embree, embreeHigh;
  auto embreeBuild = [&](std::unique_ptr<bench::EmbreeMesh>& slot, RTCBuildQuality quality) {
    slot.reset();
    auto fresh = std::make_unique<bench::EmbreeMesh>(mesh, quality);
    const double t0 = threadCpuSeconds();
    fresh->build();
    slot = std::move(fresh);
    return threadCpuSeconds() - t0;
  };
  // Interleaved like the queries (the order reversed every other run); each side times its
  // build alone, the freeing of the last one off the clock.
  Side oursBuild{"ours", 1, {}, [&] {
    world.reset();
    const double t0 = threadCpuSeconds();
    world = std::make_unique<collision::CollisionScene>(scene);
    return threadCpuSeconds() - t0;
  }};
  Side embreeDefaultBuild{"embree", 1, {}, [&] { return embreeBuild(embree, RTC_BUILD_QUALITY_MEDIUM); }};
  Side embreeHighBuild{"embree-high", 1, {}, [&] { return embreeBuild(embreeHigh, RTC_BUILD_QUALITY_HIGH); }};
  bench::runInterleaved({&oursBuild, &embreeDefaultBuild, &embreeHighBuild}, kRuns);
  out["bvh_build_cpu_ms_1m"] = oursBuild.medianMilliseconds();
  out["embree_build_cpu_ms_1m"] = embreeDefaultBuild.medianMilliseconds();
  out["embree_high_build_cpu_ms_1m"] = embreeHighBuild.medianMilliseconds();
  out["build_vs_embree"] = bench::medianTimeRatio(oursBuild, embreeDefaultBuild);
  out["build_vs_embree_high"] = bench::medianTimeRatio(oursBuild, embreeHighBuild);

  // Queries: every side answers all of them once per run; answers are kept for the check.
  const auto rays = makeRays(queryCount, 1);
  const auto spheres = makeSpheres(queryCount, 2);
  const std::size_t n = queryCount;
  std::vector<float> oursRay(n), oursRayBatch(n), oursSphere(n), oursSphereBatch(n);
  std::vector<float> embreeRay(n), embreeStream(n), embreeHighRay(n), embreePoint(n), embreeHighPoint(n);
  Side rayOurs{"ours", n, [&] { for (std::size_t i = 0; i < n; ++i) oursRay[i] = distanceOf(world->intersect(rays[i])); }};
  // Sixteen rays per call (CollisionScene::intersect(span)) against Embree's ray stream call.
  constexpr std::size_t kRayBatch = 16;
  Side rayBatchOurs{"ours-batch16", n, [&] {
    answerInBatches<kRayBatch, collision::RayHit>(rays, oursRayBatch, [&](auto q, auto r) { world->intersect(q, r); });
  }};
  Side rayEmbree{"embree", n, [&] { for (std::size_t i = 0; i < n; ++i) embreeRay[i] = embree->intersect(rays[i]); }};
  Side rayEmbreeHigh{"embree-high", n,
                     [&] { for (std::size_t i = 0; i < n; ++i) embreeHighRay[i] = embreeHigh->intersect(rays[i]); }};
  Side rayEmbreeStream{"embree-stream16", n, [&] {
    for (std::size_t i = 0; i < n; i += kRayBatch) embree->intersect16(rays.data() + i, std::min(kRayBatch, n - i), &embreeStream[i]);
  }};
  Side sphereOurs{"ours", n,
                  [&] { for (std::size_t i = 0; i < n; ++i) oursSphere[i] = distanceOf(world->sphereContact(spheres[i])); }};
  // Twelve spheres per call (two hands' contact points, as the haptic loop asks).
  constexpr std::size_t kSphereBatch = 12;
  Side sphereBatchOurs{"ours-batch12", n, [&] {
    answerInBatches<kSphereBatch, collision::SphereContact>(spheres, oursSphereBatch,
                                                            [&](auto q, auto r) { world->sphereContacts(q, r); });
  }};
  Side pointEmbree{"embree", n,
                   [&] { for (std::size_t i = 0; i < n; ++i) embreePoint[i] = embree->closestDistance(spheres[i]); }};
  Side pointEmbreeHigh{"embree-high", n, [&] {
    for (std::size_t i = 0; i < n; ++i) embreeHighPoint[i] = embreeHigh->closestDistance(spheres[i]);
  }};
  // Our single queries again under every other kernel level the CPU has (not Avx512OnAvx2:
  // a test vehicle for the AVX-512 logic, never chosen, and slow).
  const collision::SimdLevel best = collision::simdLevel();
  std::vector<collision::SimdLevel> otherLevels;
  for (collision::SimdLevel level : collision::kSimdLevels) {
    if (level != best && level != collision::SimdLevel::Avx512OnAvx2 && collision::simdLevelSupported(level)) {
      otherLevels.push_back(level);
    }
  }
  std::vector<Side> levelRays, levelSpheres;
  for (collision::SimdLevel level : otherLevels) {
    auto under = [&, level](auto&& workload) {
      return [&, level, workload] {
        collision::setSimdLevel(level);
        workload();
        collision::setSimdLevel(best);
      };
    };
    levelRays.push_back({collision::simdLevelName(level), n, under(rayOurs.workload)});
    levelSpheres.push_back({collision::simdLevelName(level), n, under(sphereOurs.workload)});
  }
  std::vector<Side*> sides{&rayOurs, &rayEmbree, &rayEmbreeHigh, &sphereOurs, &pointEmbree, &pointEmbreeHigh,
                           &rayBatchOurs, &rayEmbreeStream, &sphereBatchOurs};
  for (Side& s : levelRays) sides.push_back(&s);
  for (Side& s : levelSpheres) sides.push_back(&s);
  // An AVX2 machine's comparison on an AVX-512 one: Embree limited to AVX2 (device isa=avx2)
  // against our AVX2 kernels, both on their default trees (ours does not depend on the CPU).
  // Same code on both sides as on an AVX2-only CPU; its caches and cores are not this one's.
  const auto avx2Level = std::find(otherLevels.begin(), otherLevels.end(), collision::SimdLevel::Avx2);
  const bool avx2Pair = best == collision::SimdLevel::Avx512 && avx2Level != otherLevels.end();
  std::unique_ptr<bench::EmbreeMesh> embreeAvx2;
  std::vector<float> embreeAvx2Ray(n), embreeAvx2Point(n);
  Side rayEmbreeAvx2{"embree-avx2", n, [&] { for (std::size_t i = 0; i < n; ++i) embreeAvx2Ray[i] = embreeAvx2->intersect(rays[i]); }};
  Side pointEmbreeAvx2{"embree-avx2", n, [&] {
    for (std::size_t i = 0; i < n; ++i) embreeAvx2Point[i] = embreeAvx2->closestDistance(spheres[i]);
  }};
  if (avx2Pair) {
    embreeAvx2 = std::make_unique<bench::EmbreeMesh>(mesh, RTC_BUILD_QUALITY_MEDIUM, "avx2");
    embreeAvx2->build();  // untimed: the build figures are Embree's default device
    sides.push_back(&rayEmbreeAvx2);
    sides.push_back(&pointEmbreeAvx2);
  }
  bench::runInterleaved(sides, kRuns);

  // The answers must agree (the last run's; every run answers alike): a faster side that
  // finds other hits would not be a comparison.
  if (std::getenv(kBreakHitsVariable)) {
    const auto first = std::find_if(oursRay.begin(), oursRay.end(), [](float d) { return d != bench::kNone; });
    if (first != oursRay.end()) *first = bench::kNone;
  }
  HitCheck check;
  check.rays(mesh, rays, "rays vs embree", oursRay, embreeRay);
  check.rays(mesh, rays, "rays vs embree-high", oursRay, embreeHighRay);
  check.rays(mesh, rays, "16-ray batches vs embree stream", oursRayBatch, embreeStream);
  check.spheres("spheres vs embree point query", oursSphere, embreePoint);
  check.spheres("spheres vs embree-high point query", oursSphere, embreeHighPoint);
  check.spheres("12-sphere batches vs embree point query", oursSphereBatch, embreePoint);
  if (avx2Pair) {  // every level answers as the default does (kernel_level_tests)
    check.rays(mesh, rays, "rays vs embree isa=avx2", oursRay, embreeAvx2Ray);
    check.spheres("spheres vs embree isa=avx2 point query", oursSphere, embreeAvx2Point);
  }
  if (check.errors != 0) {
    std::fprintf(stderr, "vt_bench haptics: error: hits differ from Embree's in %zu answers (listed above): the "
                 "throughput figures would compare different work\n", check.errors);
    return 1;
  }
  out["hits_checked"] = check.checked;
  out["embree_nearest_missed"] = check.embreeMissed;

  out["simd_level"] = collision::simdLevelName(best);
  auto keyed = [](std::string name) {
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
  };
  for (const Side& s : levelRays) out["ray_mrays_per_s_" + keyed(s.name)] = s.medianMillionsPerSecond();
  for (const Side& s : levelSpheres) out["sphere_mqueries_per_s_" + keyed(s.name)] = s.medianMillionsPerSecond();
  out["ray_mrays_per_s"] = rayOurs.medianMillionsPerSecond();
  out["embree_ray_mrays_per_s"] = rayEmbree.medianMillionsPerSecond();
  out["embree_high_ray_mrays_per_s"] = rayEmbreeHigh.medianMillionsPerSecond();
  out["ray_vs_embree"] = bench::medianSpeedup(rayOurs, rayEmbree);
  out["ray_vs_embree_high"] = bench::medianSpeedup(rayOurs, rayEmbreeHigh);
  out["ray_hit_fraction"] = double(found(oursRay)) / double(n);
  out["ray_batch16_mrays_per_s"] = rayBatchOurs.medianMillionsPerSecond();
  out["embree_ray_stream16_mrays_per_s"] = rayEmbreeStream.medianMillionsPerSecond();
  out["ray_batch16_vs_embree_stream16"] = bench::medianSpeedup(rayBatchOurs, rayEmbreeStream);
  out["ray_batch16_vs_embree"] = bench::medianSpeedup(rayBatchOurs, rayEmbree);
  out["sphere_mqueries_per_s"] = sphereOurs.medianMillionsPerSecond();
  out["embree_point_mqueries_per_s"] = pointEmbree.medianMillionsPerSecond();
  out["embree_high_point_mqueries_per_s"] = pointEmbreeHigh.medianMillionsPerSecond();
  out["sphere_vs_embree_point"] = bench::medianSpeedup(sphereOurs, pointEmbree);
  out["sphere_vs_embree_high_point"] = bench::medianSpeedup(sphereOurs, pointEmbreeHigh);
  out["sphere_hit_fraction"] = double(found(oursSphere)) / double(n);
  out["sphere_batch12_mqueries_per_s"] = sphereBatchOurs.medianMillionsPerSecond();
  out["sphere_batch12_vs_embree_point"] = bench::medianSpeedup(sphereBatchOurs, pointEmbree);
  if (avx2Pair) {
    const std::size_t k = std::size_t(avx2Level - otherLevels.begin());
    out["embree_avx2_ray_mrays_per_s"] = rayEmbreeAvx2.medianMillionsPerSecond();
    out["embree_avx2_point_mqueries_per_s"] = pointEmbreeAvx2.medianMillionsPerSecond();
    out["avx2_ray_vs_embree_avx2"] = bench::medianSpeedup(levelRays[k], rayEmbreeAvx2);
    out["avx2_sphere_vs_embree_avx2_point"] = bench::medianSpeedup(levelSpheres[k], pointEmbreeAvx2);
  }

  const auto small = bumpySphereScene(100, 50);  // 10k triangles
  out["brute_ray_mrays_per_s"] = bruteRayRate(*small, std::vector(rays.begin(), rays.begin() + 2000));

  tickFigures(scene, options.quick, out);
  haptics::HapticConfig jitterConfig = haptics::HapticConfig::fiveFingertips();
  const haptics::LoopStats normal = loopRun(scene, jitterConfig, options.quick ? 0.3 : 3.0);
  out["loop_period_jitter_p50_us"] = normal.jitterP50_us;
  out["loop_period_jitter_p99_us"] = normal.jitterP99_us;
  out["loop_overruns"] = normal.overruns;
  // The same with HapticConfig::realtimePriority, when the OS allows it: SCHED_FIFO directly
  // (root, CAP_SYS_NICE), else through RealtimeKit (keys _fifo or _rtkit say which).
  jitterConfig.realtimePriority = 20;
  const haptics::LoopStats rt = loopRun(scene, jitterConfig, options.quick ? 0.3 : 3.0);
  out["loop_realtime"] = describeRealtimeGrants();
  if (rt.realtime) {
    const auto grants = realtimeGrants();
    const auto haptic = std::find_if(grants.begin(), grants.end(), [](const ThreadGrant& g) { return g.thread == "haptic"; });
    const bool fifo = haptic != grants.end() && haptic->grant.method == RealtimeMethod::SchedFifo;
    const std::string suffix = fifo ? "_fifo" : "_rtkit";
    out["loop_period_jitter_p50_us" + suffix] = rt.jitterP50_us;
    out["loop_period_jitter_p99_us" + suffix] = rt.jitterP99_us;
    out["loop_overruns" + suffix] = rt.overruns;
  }
  out["hardware_threads"] = std::thread::hardware_concurrency();

  printFigures(out, options.json);
  return 0;
}

// The tick figures alone (scripts/gpu-check.sh: the haptic thread's timing with and without
// the GPU rendering beside it).
VT_BENCH_SUITE(ticks, "haptic tick timing alone: five fingertips at 1 kHz, two hands at 4 kHz, paced and on the loop thread sleeping and spinning (1M triangles)") {
  nlohmann::json out;
  const auto scene = bumpySphereScene(options.quick ? 100 : 1000, options.quick ? 50 : 500);
  out["triangles"] = scene->meshes[0].triangleCount();
  tickFigures(scene, options.quick, out);
  printFigures(out, options.json);
  return 0;
}

// Micro-benchmarks (vt_bench micro --benchmark_filter=Haptics): single queries on 100k triangles.
namespace {

const collision::CollisionScene& microWorld() {
  static const collision::CollisionScene world(bumpySphereScene(316, 158));
  return world;
}

void HapticsRayClosestHit(benchmark::State& state) {
  const auto rays = makeRays(4096, 3);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(microWorld().intersect(rays[i++ & 4095]));
}
BENCHMARK(HapticsRayClosestHit);

void HapticsSphereContact(benchmark::State& state) {
  const auto spheres = makeSpheres(4096, 4);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(microWorld().sphereContact(spheres[i++ & 4095]));
}
BENCHMARK(HapticsSphereContact);

}  // namespace
