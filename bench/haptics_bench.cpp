// vt_bench haptics [--json] [--quick]: BVH build, ray and sphere query throughput (vs brute
// force and, when built with it, Embree 3 on the same scene and rays), haptic tick timing and
// loop period jitter. Figures are quoted in docs/PERFORMANCE.md.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <random>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench.hpp"
#include "vt/collision/collision_scene.hpp"
#include "vt/core/realtime.hpp"
#include "vt/collision/simd.hpp"
#include "vt/haptics/haptic_loop.hpp"
#include "vt/scene/demo_scene.hpp"

#include <embree3/rtcore.h>

namespace {

using namespace vt;
using WallClock = std::chrono::steady_clock;

double secondsSince(WallClock::time_point t0) { return std::chrono::duration<double>(WallClock::now() - t0).count(); }

// CPU time of the calling thread: throughput figures stay meaningful while other processes
// compete for the two cores (wall time would count the time we were not scheduled).
double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
}

// A bumpy unit sphere of about 2 * slices * stacks triangles (a dense scanned-object stand-in).
std::shared_ptr<Scene> bumpySphereScene(int slices, int stacks) {
  auto scene = std::make_shared<Scene>();
  Mesh mesh = makeSphere(slices, stacks);
  for (Vertex& v : mesh.vertices) {
    const glm::vec3 n = v.position;
    v.position = n * (1.0f + 0.02f * std::sin(40.0f * n.x) * std::sin(40.0f * n.y) * std::sin(40.0f * n.z));
  }
  scene->meshes.push_back(std::move(mesh));
  scene->vibrationMaps.push_back(makePatternVibrationMap(Pattern::Wood, 256));
  Material material;
  material.vibrationMap = 0;
  scene->materials.push_back(material);
  scene->objects.push_back({"sphere", 0, 0, glm::mat4(1.0f)});
  return scene;
}


// Rays from a radius-3 shell toward points within radius 1.2 (most hit the sphere).
std::vector<collision::Ray> makeRays(std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g;
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<collision::Ray> rays(count);
  for (auto& r : rays) {
    const glm::vec3 o = 3.0f * glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
    const glm::vec3 target = 1.2f * std::cbrt(u(rng)) * glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
    r.origin = o;
    r.direction = glm::normalize(target - o);
  }
  return rays;
}

// Fingertip-sized spheres near the surface (about half touch it).
std::vector<collision::Sphere> makeSpheres(std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g;
  std::uniform_real_distribution<float> u(-0.03f, 0.03f);
  std::vector<collision::Sphere> spheres(count);
  for (auto& s : spheres) s = {(1.0f + u(rng)) * glm::normalize(glm::vec3(g(rng), g(rng), g(rng))), 0.01f};
  return spheres;
}

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

struct EmbreeWorld {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;

  explicit EmbreeWorld(const Mesh& mesh) {
    device = rtcNewDevice("threads=1,hugepages=1");
    scene = rtcNewScene(device);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), mesh.vertices.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), mesh.triangleCount()));
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      positions.push_back(mesh.vertices[i].position);
      for (int k = 0; k < 3; ++k) vb[3 * i + std::size_t(k)] = mesh.vertices[i].position[k];
    }
    indices = mesh.indices;
    std::copy(mesh.indices.begin(), mesh.indices.end(), ib);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
  }
  ~EmbreeWorld() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
};

struct PointQueryState {
  const EmbreeWorld* world;
  float bestD2;
  unsigned prim;
};

bool closestPointCallback(RTCPointQueryFunctionArguments* args) {
  auto* state = static_cast<PointQueryState*>(args->userPtr);
  const auto& w = *state->world;
  const std::size_t base = std::size_t(args->primID) * 3;
  const glm::vec3 p(args->query->x, args->query->y, args->query->z);
  float u, v;
  const glm::vec3 q = collision::closestPointOnTriangle(p, w.positions[w.indices[base]], w.positions[w.indices[base + 1]],
                                                        w.positions[w.indices[base + 2]], u, v);
  const float d2 = glm::dot(q - p, q - p);
  if (d2 < state->bestD2) {
    state->bestD2 = d2;
    state->prim = args->primID;
    args->query->radius = std::sqrt(d2);  // shrink the search like our own query does
    return true;
  }
  return false;
}

struct TickTiming {
  haptics::LoopStats loop;          // the loop's own figures (wall time per tick)
  double cpuP50_us = 0.0, cpuP99_us = 0.0;  // thread CPU time per tick: preemption excluded
};

// Ticks `config`'s loop on the calling thread over hands sliding on the surface: poseAt(pose, a)
// places the joints of tick i at angle a = 0.001 i around the sphere.
template <class PoseAt>
TickTiming tickTiming(std::shared_ptr<Scene> scene, haptics::HapticConfig config, int ticks, PoseAt&& poseAt) {
  auto history = std::make_unique<PoseHistory>();
  PoseHistory& poses = *history;
  config.sampling.timeout_ns = 0;
  config.renderer.model = haptics::TactileModel::TextureWaveform;
  haptics::HapticLoop loop(config, poses);
  loop.publishScene(haptics::makeHapticScene(std::move(scene)));
  std::vector<double> cpu_us;
  cpu_us.reserve(std::size_t(ticks));
  for (int i = 0; i < ticks; ++i) {
    HandPose pose;
    pose.valid = true;
    for (auto& r : pose.radius_m) r = kDefaultFingertipRadius_m;
    poseAt(pose, 0.001f * float(i));
    pose.t_ns = std::int64_t(i) * 1'000'000;
    poses.publish(pose);
    const double t0 = threadCpuSeconds();
    loop.tickOnce(pose.t_ns);
    cpu_us.push_back((threadCpuSeconds() - t0) * 1e6);
  }
  std::sort(cpu_us.begin(), cpu_us.end());
  return {loop.stats(), cpu_us[cpu_us.size() / 2], cpu_us[cpu_us.size() * 99 / 100]};
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

haptics::LoopStats loopRun(std::shared_ptr<Scene> scene, double seconds, int realtimePriority) {
  auto history = std::make_unique<PoseHistory>();
  const PoseHistory& poses = *history;
  haptics::HapticConfig config = haptics::HapticConfig::fiveFingertips();
  config.realtimePriority = realtimePriority;
  haptics::HapticLoop loop(config, poses);
  SpscRing<haptics::ActuatorFrame> ring(8192);
  loop.addOutput(ring);
  loop.publishScene(haptics::makeHapticScene(std::move(scene)));
  loop.start();
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  loop.stop();
  return loop.stats();
}

}  // namespace

// Times `query(i)` over [0, n) in kRounds chunks. Suites measuring two engines interleave
// their chunks (A, B, A, B, ...) so load from other processes hits both alike.
constexpr int kRounds = 10;

struct Throughput {
  double seconds = 0.0;
  std::size_t hits = 0, count = 0;
  double mPerS() const { return seconds > 0.0 ? double(count) / seconds / 1e6 : 0.0; }
  double hitFraction() const { return count ? double(hits) / double(count) : 0.0; }
};

template <class Query>
void timeChunk(Throughput& t, std::size_t n, int round, Query&& query) {
  const std::size_t begin = n * std::size_t(round) / kRounds, end = n * std::size_t(round + 1) / kRounds;
  const double t0 = threadCpuSeconds();
  for (std::size_t i = begin; i < end; ++i) t.hits += query(i);
  t.seconds += threadCpuSeconds() - t0;
  t.count += end - begin;
}

VT_BENCH_SUITE(haptics, "BVH build, ray/sphere queries (vs brute force and Embree), haptic tick") {
  const int slices = options.quick ? 100 : 1000, stacks = options.quick ? 50 : 500;
  const std::size_t rayCount = options.quick ? 20'000 : 500'000;
  nlohmann::json out;

  auto scene = bumpySphereScene(slices, stacks);
  auto t0 = WallClock::now();
  double cpu0 = threadCpuSeconds();
  const collision::CollisionScene world(scene);
  out["bvh_build_ms_1m"] = secondsSince(t0) * 1e3;
  out["bvh_build_cpu_ms_1m"] = (threadCpuSeconds() - cpu0) * 1e3;
  out["triangles"] = scene->meshes[0].triangleCount();
  const auto rays = makeRays(rayCount, 1);
  const auto spheres = makeSpheres(rayCount, 2);
  Throughput ours, oursSphere;
  auto ourRay = [&](std::size_t i) { return world.intersect(rays[i]).hit(); };
  // Sixteen rays per call (CollisionScene::intersect(span)); Embree's counterpart is its ray
  // stream call rtcIntersect1M.
  constexpr std::size_t kRayBatch = 16;
  Throughput oursRayBatch;
  auto ourRayBatch = [&](std::size_t i) {
    if (i % kRayBatch != 0) return std::size_t(0);
    collision::RayHit hits[kRayBatch];
    const std::size_t count = std::min(kRayBatch, rays.size() - i);
    world.intersect({rays.data() + i, count}, {hits, count});
    std::size_t n = 0;
    for (std::size_t k = 0; k < count; ++k) n += hits[k].hit();
    return n;
  };
  auto ourSphere = [&](std::size_t i) { return world.sphereContact(spheres[i]).hit(); };
  // Twelve spheres per call (two hands' contact points, as the haptic loop asks).
  constexpr std::size_t kBatch = 12;
  Throughput oursBatch;
  auto ourSphereBatch = [&](std::size_t i) {
    if (i % kBatch != 0) return std::size_t(0);
    collision::SphereContact contacts[kBatch];
    const std::size_t count = std::min(kBatch, spheres.size() - i);
    world.sphereContacts({spheres.data() + i, count}, {contacts, count});
    std::size_t hits = 0;
    for (std::size_t k = 0; k < count; ++k) hits += contacts[k].hit();
    return hits;
  };

  t0 = WallClock::now();
  cpu0 = threadCpuSeconds();
  const EmbreeWorld embree(scene->meshes[0]);  // threads=1: builds on this thread
  out["embree_build_ms_1m"] = secondsSince(t0) * 1e3;
  out["embree_build_cpu_ms_1m"] = (threadCpuSeconds() - cpu0) * 1e3;
  // The builds above are each side's first (cold caches, Embree's first device): the fastest of
  // three more, alternating, compares the builders warm.
  double oursWarm_ms = 1e30, embreeWarm_ms = 1e30;
  for (int round = 0; round < 3; ++round) {
    cpu0 = threadCpuSeconds();
    {
      const collision::CollisionScene again(scene);
      oursWarm_ms = std::min(oursWarm_ms, (threadCpuSeconds() - cpu0) * 1e3);
    }
    cpu0 = threadCpuSeconds();
    {
      const EmbreeWorld again(scene->meshes[0]);
      embreeWarm_ms = std::min(embreeWarm_ms, (threadCpuSeconds() - cpu0) * 1e3);
    }
  }
  out["bvh_build_cpu_ms_1m_warm"] = oursWarm_ms;
  out["embree_build_cpu_ms_1m_warm"] = embreeWarm_ms;
  out["build_vs_embree_warm"] = oursWarm_ms / embreeWarm_ms;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  auto embreeRay = [&](std::size_t i) {
    const collision::Ray& r = rays[i];
    RTCRayHit rh{};
    rh.ray.org_x = r.origin.x, rh.ray.org_y = r.origin.y, rh.ray.org_z = r.origin.z;
    rh.ray.dir_x = r.direction.x, rh.ray.dir_y = r.direction.y, rh.ray.dir_z = r.direction.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = r.tMax;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree.scene, &context, &rh);
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  };
  auto embreeRayStream = [&](std::size_t i) {
    if (i % kRayBatch != 0) return std::size_t(0);
    RTCRayHit rh[kRayBatch]{};
    const std::size_t count = std::min(kRayBatch, rays.size() - i);
    for (std::size_t k = 0; k < count; ++k) {
      const collision::Ray& r = rays[i + k];
      rh[k].ray.org_x = r.origin.x, rh[k].ray.org_y = r.origin.y, rh[k].ray.org_z = r.origin.z;
      rh[k].ray.dir_x = r.direction.x, rh[k].ray.dir_y = r.direction.y, rh[k].ray.dir_z = r.direction.z;
      rh[k].ray.tfar = r.tMax;
      rh[k].ray.mask = 0xffffffffu;
      rh[k].hit.geomID = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect1M(embree.scene, &context, rh, unsigned(count), sizeof(RTCRayHit));
    std::size_t n = 0;
    for (std::size_t k = 0; k < count; ++k) n += rh[k].hit.geomID != RTC_INVALID_GEOMETRY_ID;
    return n;
  };
  auto embreePoint = [&](std::size_t i) {
    const collision::Sphere& s = spheres[i];
    RTCPointQuery query{};
    query.x = s.center.x, query.y = s.center.y, query.z = s.center.z;
    query.radius = s.radius_m;
    RTCPointQueryContext pqContext;
    rtcInitPointQueryContext(&pqContext);
    PointQueryState state{&embree, s.radius_m * s.radius_m, RTC_INVALID_GEOMETRY_ID};
    rtcPointQuery(embree.scene, &query, &pqContext, closestPointCallback, &state);
    return state.prim != RTC_INVALID_GEOMETRY_ID;
  };
  Throughput theirs, theirsPoint, oursSse2, oursSphereSse2, theirsStream;
  const collision::SimdLevel best = collision::simdLevel();
  for (int round = 0; round < kRounds; ++round) {
    timeChunk(ours, rays.size(), round, ourRay);
    timeChunk(theirs, rays.size(), round, embreeRay);
    timeChunk(oursSphere, spheres.size(), round, ourSphere);
    timeChunk(theirsPoint, spheres.size(), round, embreePoint);
    timeChunk(oursBatch, spheres.size(), round, ourSphereBatch);
    timeChunk(oursRayBatch, rays.size(), round, ourRayBatch);
    timeChunk(theirsStream, rays.size(), round, embreeRayStream);
    collision::setSimdLevel(collision::SimdLevel::Sse2);  // the baseline kernels, for comparison
    timeChunk(oursSse2, rays.size(), round, ourRay);
    timeChunk(oursSphereSse2, spheres.size(), round, ourSphere);
    collision::setSimdLevel(best);
  }
  out["simd_level"] = collision::simdLevelName(best);
  out["ray_mrays_per_s_sse2"] = oursSse2.mPerS();
  out["sphere_mqueries_per_s_sse2"] = oursSphereSse2.mPerS();
  out["embree_ray_mrays_per_s"] = theirs.mPerS();
  out["embree_ray_hit_fraction"] = theirs.hitFraction();
  out["embree_point_mqueries_per_s"] = theirsPoint.mPerS();
  out["embree_point_hit_fraction"] = theirsPoint.hitFraction();
  out["ray_vs_embree"] = ours.mPerS() / theirs.mPerS();
  out["sphere_vs_embree_point"] = oursSphere.mPerS() / theirsPoint.mPerS();
  out["sphere_batch12_vs_embree_point"] = oursBatch.mPerS() / theirsPoint.mPerS();
  out["embree_ray_stream16_mrays_per_s"] = theirsStream.mPerS();
  out["ray_batch16_vs_embree_stream16"] = oursRayBatch.mPerS() / theirsStream.mPerS();
  out["ray_batch16_vs_embree"] = oursRayBatch.mPerS() / theirs.mPerS();
  out["ray_mrays_per_s"] = ours.mPerS();
  out["ray_hit_fraction"] = ours.hitFraction();
  out["ray_batch16_mrays_per_s"] = oursRayBatch.mPerS();
  out["ray_batch16_hit_fraction"] = oursRayBatch.hitFraction();
  out["sphere_mqueries_per_s"] = oursSphere.mPerS();
  out["sphere_hit_fraction"] = oursSphere.hitFraction();
  out["sphere_batch12_mqueries_per_s"] = oursBatch.mPerS();
  out["sphere_batch12_hit_fraction"] = oursBatch.hitFraction();

  const auto small = bumpySphereScene(100, 50);  // 10k triangles
  out["brute_ray_mrays_per_s"] = bruteRayRate(*small, std::vector(rays.begin(), rays.begin() + 2000));

  const TickTiming ticks =
      tickTiming(scene, haptics::HapticConfig::fiveFingertips(), options.quick ? 2000 : 20000, fiveFingertipPose);
  out["tick_p50_us"] = ticks.loop.tickP50_us;
  out["tick_p99_us"] = ticks.loop.tickP99_us;
  out["tick_max_us"] = ticks.loop.tickMax_us;
  out["tick_cpu_p99_us"] = ticks.cpuP99_us;
  const TickTiming twoHands = tickTiming(scene, twoHandsConfig(), options.quick ? 2000 : 20000, twoHandsPose);
  out["two_hands_4khz_tick_p50_us"] = twoHands.loop.tickP50_us;
  out["two_hands_4khz_tick_p99_us"] = twoHands.loop.tickP99_us;
  out["two_hands_4khz_tick_max_us"] = twoHands.loop.tickMax_us;
  out["two_hands_4khz_tick_cpu_p50_us"] = twoHands.cpuP50_us;
  out["two_hands_4khz_tick_cpu_p99_us"] = twoHands.cpuP99_us;
  const haptics::LoopStats normal = loopRun(scene, options.quick ? 0.3 : 3.0, 0);
  out["loop_period_jitter_p50_us"] = normal.jitterP50_us;
  out["loop_period_jitter_p99_us"] = normal.jitterP99_us;
  out["loop_overruns"] = normal.overruns;
  // The same with HapticConfig::realtimePriority, when the OS allows it: SCHED_FIFO directly
  // (root, CAP_SYS_NICE), else through RealtimeKit (keys _fifo or _rtkit say which).
  const haptics::LoopStats rt = loopRun(scene, options.quick ? 0.3 : 3.0, 20);
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

  if (options.json) {
    std::printf("%s\n", out.dump().c_str());
  } else {
    for (const auto& [key, value] : out.items()) std::printf("%-32s %s\n", key.c_str(), value.dump().c_str());
  }
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
