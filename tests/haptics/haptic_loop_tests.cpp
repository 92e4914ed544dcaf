#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>

#include "test_support.hpp"
#include "vt/haptics/haptic_loop.hpp"

using namespace vt;
using namespace vt::haptics;

namespace {

// A 20 cm tactile plate at y = 0 (u = x / 0.2 + 0.5, v = 0.5 - z / 0.2) with a given map.
std::shared_ptr<Scene> plateScene(ImageF map, float gain = 0.5f) {
  auto scene = std::make_shared<Scene>();
  scene->meshes.push_back(makePlane({0.2f, 0.2f}, 1));
  scene->vibrationMaps.push_back(std::move(map));
  Material material;
  material.name = "plate";
  material.vibrationMap = 0;
  material.tactileGain = gain;
  scene->materials.push_back(material);
  scene->objects.push_back({"plate", 0, 0, glm::mat4(1.0f)});
  return scene;
}

ImageF constantImage(float value) {
  ImageF map(4, 4, 1);
  for (float& p : map.pixels) p = value;
  return map;
}

// A pose with every joint far away except the given fingertips, placed at `tips`.
HandPose poseWithTips(std::int64_t t_ns, std::initializer_list<std::pair<HandJoint, glm::vec3>> tips) {
  HandPose pose;
  pose.t_ns = t_ns;
  pose.valid = true;
  for (auto& p : pose.position) p = glm::vec3(100.0f);
  for (auto& r : pose.radius_m) r = 0.008f;
  for (const auto& [joint, position] : tips) pose.position[std::size_t(joint)] = position;
  return pose;
}

std::vector<ActuatorFrame> drain(SpscRing<ActuatorFrame>& ring) {
  std::vector<ActuatorFrame> frames;
  ActuatorFrame f;
  while (ring.pop(f)) frames.push_back(f);
  return frames;
}

using vt::test::kMs;

}  // namespace

TEST_CASE("Ticks turn a pressed fingertip into the paper intensity on its actuator") {
  PoseHistory poses;
  ManualClock clock;
  HapticConfig config = HapticConfig::fiveFingertips();
  config.routes[1].gain = 0.5f;  // index actuator at half gain
  HapticLoop loop(config, poses, clock);
  SpscRing<ActuatorFrame> ring(64);
  SpscRing<ContactTrace> traces(256);
  loop.addOutput(ring);
  loop.setTraceOutput(traces);
  loop.publishScene(makeHapticScene(plateScene(constantImage(0.8f))));

  // Index tip 6 mm above the plate with an 8 mm radius: 2 mm deep at u = 0.75, v = 0.25.
  poses.publish(poseWithTips(0, {{HandJoint::IndexTip, {0.05f, 0.006f, 0.05f}}}));
  for (int i = 0; i < 3; ++i) REQUIRE(loop.tickOnce(i * kMs));
  const auto frames = drain(ring);
  REQUIRE(frames.size() == 3);
  const float expected = paperIntensity(0.8f, 0.002f, 0.5f);
  CHECK(expected == Approx(0.8f * 1.02f * 0.5f));
  CHECK(frames[0].intensity[1] < frames[2].intensity[1]);  // onset ramp
  CHECK(frames[2].intensity[1] == Approx(0.5f * expected).epsilon(1e-4));
  CHECK(frames[2].actuatorCount == 5);
  CHECK(frames[2].blockLength == 8);
  CHECK(frames[2].sampleRate_hz == 8000);
  CHECK(frames[2].sequence == 2);
  for (int a : {0, 2, 3, 4}) CHECK(frames[2].intensity[std::size_t(a)] == 0.0f);

  ContactTrace t;
  int index = 0;
  while (traces.pop(t)) {
    if (t.contact != 1) {
      CHECK_FALSE(t.inContact);
      continue;
    }
    ++index;
    CHECK(t.inContact);
    CHECK(t.object == 0);
    CHECK(t.material == 0);
    CHECK(t.u == Approx(0.75f));
    CHECK(t.v == Approx(0.25f));
    CHECK(t.depth_m == Approx(0.002f).margin(1e-6));
    CHECK(t.mapValue == Approx(0.8f));
  }
  CHECK(index == 3);
}

TEST_CASE("The vtouching preset drives index middle and ring with response curves") {
  PoseHistory poses;
  ManualClock clock;
  HapticConfig config = HapticConfig::vTouching();
  REQUIRE(config.contacts.size() == 3);
  config.routes[2].curve = {2.0f, 0.1f};  // ring: squared, with a 10 % floor
  HapticLoop loop(config, poses, clock);
  LatestValue<ActuatorFrame> mailbox;
  loop.addOutput(mailbox);
  loop.publishScene(makeHapticScene(plateScene(constantImage(0.5f), 1.0f)));
  poses.publish(poseWithTips(0, {{HandJoint::ThumbTip, {0.0f, 0.0f, 0.0f}},
                                 {HandJoint::MiddleTip, {0.0f, 0.007f, 0.0f}},
                                 {HandJoint::RingTip, {0.02f, 0.007f, 0.0f}}}));
  for (int i = 0; i < 3; ++i) loop.tickOnce(i * kMs);
  ActuatorFrame frame;
  REQUIRE(mailbox.read(frame));
  CHECK(frame.actuatorCount == 4);
  CHECK(frame.intensity[std::size_t(ActuatorId::Thumb)] == 0.0f);  // thumb is not routed
  CHECK(frame.intensity[std::size_t(ActuatorId::Index)] == 0.0f);  // index is in the air
  const float level = 0.5f * 1.01f;  // 1 mm deep, gain 1
  CHECK(frame.intensity[std::size_t(ActuatorId::Middle)] == Approx(level).epsilon(1e-4));
  CHECK(frame.intensity[std::size_t(ActuatorId::Ring)] == Approx(0.1f + 0.9f * level * level).epsilon(1e-4));
  CHECK(config.routes[2].curve.apply(0.0f) == 0.0f);
}

TEST_CASE("Stale or missing poses and a missing scene give silent frames") {
  PoseHistory poses;
  ManualClock clock;
  HapticLoop loop(HapticConfig::fiveFingertips(), poses, clock);
  SpscRing<ActuatorFrame> ring(64);
  loop.addOutput(ring);
  loop.tickOnce(0);  // no pose, no scene
  poses.publish(poseWithTips(0, {{HandJoint::IndexTip, {0.0f, 0.0f, 0.0f}}}));
  loop.tickOnce(1 * kMs);  // pose but no scene
  loop.publishScene(makeHapticScene(plateScene(constantImage(1.0f))));
  loop.tickOnce(2 * kMs);
  loop.tickOnce(3 * kMs);
  loop.tickOnce(200 * kMs);  // the pose is 200 ms old: treated as no hand
  loop.tickOnce(201 * kMs);
  const auto frames = drain(ring);
  REQUIRE(frames.size() == 6);
  CHECK(frames[0].intensity[1] == 0.0f);
  CHECK(frames[1].intensity[1] == 0.0f);
  CHECK(frames[3].intensity[1] > 0.0f);
  CHECK(frames[5].intensity[1] == 0.0f);
  CHECK(frames[5].block[1][7] == 0.0f);  // released within 2 ms (two ticks)
  CHECK(loop.stats().stalePoses >= 3);
}

TEST_CASE("Published snapshots replace the scene and old ones are freed off the haptic thread") {
  PoseHistory poses;
  ManualClock clock;
  HapticLoop loop(HapticConfig::fiveFingertips(), poses, clock);
  LatestValue<ActuatorFrame> mailbox;
  loop.addOutput(mailbox);
  auto scene = plateScene(constantImage(1.0f));
  auto first = makeHapticScene(scene);
  const std::weak_ptr<const HapticScene> firstWeak = first;
  loop.publishScene(std::move(first));
  poses.publish(poseWithTips(0, {{HandJoint::IndexTip, {0.0f, 0.004f, 0.0f}}}));
  for (int i = 0; i < 3; ++i) loop.tickOnce(i * kMs);
  ActuatorFrame frame;
  REQUIRE(mailbox.read(frame));
  CHECK(frame.intensity[1] > 0.0f);

  // Move the plate away: a new snapshot of the edited scene.
  auto edited = std::make_shared<Scene>(*scene);
  edited->objects[0].T_world_object = glm::translate(glm::mat4(1.0f), {0.0f, -1.0f, 0.0f});
  loop.publishScene(makeHapticScene(std::move(edited)));
  CHECK(loop.liveSnapshots() == 2);  // the haptic thread has not moved past the first yet
  CHECK_FALSE(firstWeak.expired());
  for (int i = 3; i < 6; ++i) loop.tickOnce(i * kMs);
  REQUIRE(mailbox.read(frame));
  CHECK(frame.intensity[1] == 0.0f);  // released
  loop.reclaim();
  CHECK(loop.liveSnapshots() == 1);
  CHECK(firstWeak.expired());
}

TEST_CASE("The loop thread delivers frames at the configured rate and stops silent") {
  const LoopPacing pacing = GENERATE(LoopPacing::Sleep, LoopPacing::Spin);
  CAPTURE(loopPacingName(pacing));
  PoseHistory poses;
  HapticConfig config = HapticConfig::fiveFingertips();
  config.rate_hz = 1000.0f;
  config.pacing = pacing;
  config.sampling.timeout_ns = 0;
  config.realtimePriority = 10;  // best effort: keeps the rate on a loaded machine when allowed
  HapticLoop loop(config, poses);
  SpscRing<ActuatorFrame> ring(4096);
  loop.addOutput(ring);
  loop.publishScene(makeHapticScene(plateScene(constantImage(1.0f))));
  poses.publish(poseWithTips(0, {{HandJoint::IndexTip, {0.0f, 0.004f, 0.0f}}}));
  const std::clock_t cpu0 = std::clock();  // process CPU time: the loop thread's, this one sleeps
  const auto wall0 = std::chrono::steady_clock::now();
  loop.start();
  CHECK_FALSE(loop.tickOnce(0));  // one producer at a time
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  loop.stop();
  const double cpu_s = double(std::clock() - cpu0) / CLOCKS_PER_SEC;
  // The loop ran from start() to stop(): longer than 400 ms when this thread woke late (a
  // spinning real-time loop holds one of two cores while another test holds the other).
  const double ran_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall0).count();
  // Spinning keeps the loop thread on its core the whole 400 ms (sleeping: 0.015 s of CPU here;
  // the bound leaves room for a loaded machine); sleeping frees it between ticks
  // (no bound asserted: a slow tick under a sanitizer may take a good part of each period).
  if (pacing == LoopPacing::Spin) CHECK(cpu_s > 0.1);
  const auto frames = drain(ring);
  // At 1 kHz one frame a millisecond it ran; generous bounds for a loaded 2-core machine (missed
  // periods are skipped, never bunched up).
  CAPTURE(ran_ms);
  REQUIRE(frames.size() >= 100);
  CHECK(double(frames.size()) <= 1.2 * ran_ms);
  std::vector<std::int64_t> spacing;
  for (std::size_t i = 1; i + 1 < frames.size(); ++i) {
    CHECK(frames[i].t_ns > frames[i - 1].t_ns);
    spacing.push_back(frames[i].t_ns - frames[i - 1].t_ns);
  }
  std::nth_element(spacing.begin(), spacing.begin() + std::ptrdiff_t(spacing.size() / 2), spacing.end());
  const std::int64_t median = spacing[spacing.size() / 2];
  CHECK(median >= 900'000);   // never faster than the configured rate
  CHECK(median <= 1'500'000);
  CHECK(frames[frames.size() / 2].intensity[1] > 0.0f);
  CHECK(frames.back().intensity[1] == 0.0f);  // the stop frame
  const LoopStats stats = loop.stats();
  CHECK(stats.ticks + 1 == frames.size());
  CHECK(stats.tickP50_us > 0.0);
  CHECK(stats.tickP99_us >= stats.tickP50_us);
  CHECK(stats.jitterP99_us >= stats.jitterP50_us);
  CHECK(loop.heartbeat() == stats.ticks);
  // Every tick of the run, to 1 us (the bins' upper edges); the window's figures are exact.
  CHECK(stats.runTickP50_us >= 1.0);
  CHECK(stats.runTickP99_us >= stats.runTickP50_us);
  CHECK(stats.runTickMax_us >= stats.tickMax_us);
}

TEST_CASE("TickHistogram gives percentiles of every tick to 1 us") {
  TickHistogram ticks;
  CHECK(ticks.percentile_us(0.99) == 0.0);
  for (int i = 0; i < 97; ++i) ticks.add(5'200);
  ticks.add(40'700);
  ticks.add(999'999);
  ticks.add(2'000'000);  // past the last bin's lower edge: its own time is the answer
  REQUIRE(ticks.count() == 100);
  CHECK(ticks.percentile_us(0.5) == 6.0);
  CHECK(ticks.percentile_us(0.97) == 41.0);
  CHECK(ticks.percentile_us(0.98) == 1000.0);
  CHECK(ticks.percentile_us(0.99) == 2000.0);
  CHECK(ticks.percentile_us(1.0) == 2000.0);
  CHECK(ticks.max_us() == 2000.0);
}

TEST_CASE("Loop pacing names round-trip and an unknown one is refused") {
  LoopPacing pacing = LoopPacing::Sleep;
  CHECK(parseLoopPacing("spin", pacing));
  CHECK(pacing == LoopPacing::Spin);
  CHECK(std::string(loopPacingName(pacing)) == "spin");
  CHECK(parseLoopPacing("sleep", pacing));
  CHECK(pacing == LoopPacing::Sleep);
  CHECK_FALSE(parseLoopPacing("busy", pacing));
  CHECK(pacing == LoopPacing::Sleep);
}

TEST_CASE("A ManualClock drives the loop thread deterministically") {
  const LoopPacing pacing = GENERATE(LoopPacing::Sleep, LoopPacing::Spin);
  CAPTURE(loopPacingName(pacing));
  PoseHistory poses;
  ManualClock clock;
  HapticConfig config = HapticConfig::fiveFingertips();
  config.rate_hz = 4000.0f;  // 2 samples per tick at 8 kHz
  config.pacing = pacing;
  HapticLoop loop(config, poses, clock);
  SpscRing<ActuatorFrame> ring(1024);
  loop.addOutput(ring);
  loop.start();
  while (loop.heartbeat() < 100) std::this_thread::yield();
  loop.stop();
  const auto frames = drain(ring);
  REQUIRE(frames.size() > 100);
  for (std::size_t i = 1; i + 1 < frames.size(); ++i) CHECK(frames[i].t_ns - frames[i - 1].t_ns == 250'000);
  CHECK(frames[0].blockLength == 2);
  CHECK(loop.stats().jitterP99_us == 0.0);
}

TEST_CASE("Invalid configurations are rejected naming the field") {
  PoseHistory poses;
  HapticConfig config = HapticConfig::fiveFingertips();
  config.rate_hz = 5000.0f;
  CHECK_THROWS_WITH(HapticLoop(config, poses), Catch::Contains("rate_hz"));
  config = HapticConfig::fiveFingertips();
  config.rate_hz = 3000.0f;  // 8000 / 3000 is not a whole number of samples
  CHECK_THROWS_WITH(HapticLoop(config, poses), Catch::Contains("sampleRate_hz"));
  config = HapticConfig::fiveFingertips();
  config.routes[0].contact = 9;
  CHECK_THROWS_WITH(HapticLoop(config, poses), Catch::Contains("routes[0].contact"));
  config = HapticConfig::fiveFingertips();
  config.pacing = LoopPacing(7);
  CHECK_THROWS_WITH(HapticLoop(config, poses), Catch::Contains("pacing 7"));
}

TEST_CASE("A sweep over a dataset map gives an intensity trace that follows the map brightness") {
  const auto dir = vt::test::datasetDir();
  if (!dir) VT_SKIP("dataset not found");
  const auto path = *dir / "pattern_board" / "pattern_board_acc.png";
  const ImageF map = loadChannelAsFloat(path, 0);
  PoseHistory poses;
  ManualClock clock;
  HapticConfig config = HapticConfig::vTouching();
  HapticLoop loop(config, poses, clock);
  SpscRing<ContactTrace> traces(8192);
  loop.setTraceOutput(traces);
  loop.publishScene(makeHapticScene(plateScene(map, 1.0f)));
  // The index tip slides diagonally across the plate, 1 mm deep, over 1000 ticks.
  const int ticks = 1000;
  std::vector<double> trace, brightness;
  for (int i = 0; i < ticks; ++i) {
    const float s = float(i) / float(ticks - 1);
    const glm::vec3 tip{-0.09f + 0.18f * s, 0.007f, 0.08f - 0.16f * s};
    poses.publish(poseWithTips(i * kMs, {{HandJoint::IndexTip, tip}}));
    loop.tickOnce(i * kMs);
    ContactTrace t;
    while (traces.pop(t)) {
      if (t.contact != 0 || i < 3) continue;
      REQUIRE(t.inContact);
      // Independent reference: the nearest pixel by row = (1 - v) * h, col = u * w.
      const float u = tip.x / 0.2f + 0.5f, v = 0.5f - tip.z / 0.2f;
      const int col = std::min(int(u * float(map.width)), map.width - 1);
      const int row = std::min(int((1.0f - v) * float(map.height)), map.height - 1);
      CHECK(t.u == Approx(u).margin(1e-4));
      CHECK(t.v == Approx(v).margin(1e-4));
      trace.push_back(t.intensity);
      brightness.push_back(map.at(col, row));
    }
  }
  REQUIRE(trace.size() > 900);
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < trace.size(); ++i) ma += trace[i], mb += brightness[i];
  ma /= double(trace.size());
  mb /= double(trace.size());
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < trace.size(); ++i) {
    sab += (trace[i] - ma) * (brightness[i] - mb);
    saa += (trace[i] - ma) * (trace[i] - ma);
    sbb += (brightness[i] - mb) * (brightness[i] - mb);
  }
  REQUIRE(sbb > 0.0);  // the path crosses texture, not a blank area
  const double correlation = sab / std::sqrt(saa * sbb);
  INFO("correlation " << correlation << " mean brightness " << mb);
  CHECK(correlation > 0.9);
}

namespace {

// The index tip's contact UV per tick while the tip slides at 0.1 m/s along x, 1 mm deep,
// with poses arriving at `poseRate_hz` (stamped with the time they describe) and ticks at 1 kHz.
std::vector<float> slideUvSteps(PoseSampling mode, double poseRate_hz) {
  PoseHistory poses;
  ManualClock clock;
  HapticConfig config = HapticConfig::fiveFingertips();
  config.sampling.mode = mode;
  HapticLoop loop(config, poses, clock);
  SpscRing<ContactTrace> traces(16384);
  loop.setTraceOutput(traces);
  loop.publishScene(makeHapticScene(plateScene(constantImage(0.5f))));
  auto tipAt = [](std::int64_t t_ns) { return glm::vec3(-0.08f + 0.1f * float(double(t_ns) * 1e-9), 0.007f, 0.0f); };
  const auto posePeriod_ns = std::int64_t(1e9 / poseRate_hz);
  std::int64_t nextPose_ns = 0;
  std::vector<float> steps;
  float lastU = -1.0f;
  for (std::int64_t t = 0; t < 1000 * kMs; t += kMs) {
    // A pose becomes available when its frame is done, one pose period after the time it describes.
    while (nextPose_ns + posePeriod_ns <= t) {
      poses.publish(poseWithTips(nextPose_ns, {{HandJoint::IndexTip, tipAt(nextPose_ns)}}));
      nextPose_ns += posePeriod_ns;
    }
    loop.tickOnce(t);
    ContactTrace trace;
    while (traces.pop(trace)) {
      if (trace.contact != 1 || !trace.inContact) continue;
      if (lastU >= 0.0f && t > 200 * kMs) steps.push_back((trace.u - lastU) / (0.1f * 0.001f / 0.2f));
      lastU = trace.u;
    }
  }
  return steps;
}

float percentile(std::vector<float> v, double p) {
  std::sort(v.begin(), v.end());
  return v[std::size_t(p * double(v.size() - 1))];
}

}  // namespace

TEST_CASE("With poses at 30 Hz the loop sweeps the surface at the hand's speed every tick, unlike the newest pose") {
  const std::vector<float> predicted = slideUvSteps(PoseSampling::Predict, 30.0);
  REQUIRE(predicted.size() > 700);
  // Every tick advances by the true per-tick travel: no bursts, no silent repeats.
  CHECK(percentile(predicted, 0.01) > 0.9f);
  CHECK(percentile(predicted, 0.99) < 1.1f);
  const std::vector<float> interpolated = slideUvSteps(PoseSampling::Interpolate, 30.0);
  CHECK(percentile(interpolated, 0.01) > 0.9f);
  CHECK(percentile(interpolated, 0.99) < 1.1f);
  // The newest pose alone: the UV stands still for a frame, then jumps a frame's travel at once.
  const std::vector<float> latest = slideUvSteps(PoseSampling::Latest, 30.0);
  CHECK(percentile(latest, 0.5) == Approx(0.0f).margin(1e-3));
  CHECK(percentile(latest, 0.999) > 25.0f);
}

TEST_CASE("A reset between two poses is not swept across") {
  PoseHistory poses;
  ManualClock clock;
  HapticLoop loop(HapticConfig::fiveFingertips(), poses, clock);
  SpscRing<ContactTrace> traces(256);
  loop.setTraceOutput(traces);
  loop.publishScene(makeHapticScene(plateScene(constantImage(0.5f))));
  poses.publish(poseWithTips(0, {{HandJoint::IndexTip, {-0.05f, 0.007f, 0.0f}}}));
  loop.tickOnce(0);
  // Reset 1 cm away (slow enough to pass for motion, but flagged by the source).
  poses.publish(poseWithTips(10 * kMs, {{HandJoint::IndexTip, {-0.04f, 0.007f, 0.0f}}}), true);
  for (int i = 1; i <= 12; ++i) loop.tickOnce(i * kMs);
  ContactTrace t;
  std::vector<float> u;
  while (traces.pop(t))
    if (t.contact == 1 && t.inContact) u.push_back(t.u);
  REQUIRE(u.size() == 13);
  // Before the reset's time the hand holds its old place; then it is at the new one at once.
  for (int i = 0; i < 10; ++i) CHECK(u[std::size_t(i)] == Approx(0.25f));
  CHECK(u[10] == Approx(0.3f));
}
