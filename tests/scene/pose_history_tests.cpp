#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <memory>
#include <random>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>

#include "vt/scene/pose_history.hpp"
#include "test_support.hpp"

namespace {

using vt::test::kMs;
const glm::vec3 kVelocity_mps{0.1f, 0.0f, -0.05f};

// A hand whose palm is at `p` (every joint moves with it).
vt::HandPose handAt(glm::vec3 p, std::int64_t t_ns) {
  return vt::poseHand(glm::translate(glm::mat4(1.0f), p), {}, false, t_ns);
}

glm::vec3 truePalm(std::int64_t t_ns) { return kVelocity_mps * float(double(t_ns) * 1e-9); }

glm::vec3 palm(const vt::PoseSample& s) { return s.pose.at(vt::HandJoint::Palm); }

vt::PoseSamplingConfig mode(vt::PoseSampling m) {
  vt::PoseSamplingConfig config;
  config.mode = m;
  return config;
}

}  // namespace

TEST_CASE("PoseHistory interpolates a steady slide exactly between poses at 30 Hz") {
  auto history = std::make_unique<vt::PoseHistory>();
  const std::int64_t period = 33 * kMs;
  for (int i = 0; i < 20; ++i) REQUIRE(history->publish(handAt(truePalm(i * period), i * period)));
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::int64_t> t(0, 19 * period);
  for (int k = 0; k < 500; ++k) {
    const std::int64_t at = t(rng);
    const vt::PoseSample s = history->sample(at, mode(vt::PoseSampling::Predict));
    REQUIRE(s.pose.valid);
    CHECK(s.pose.t_ns == at);
    CHECK(glm::length(palm(s) - truePalm(at)) < 1e-6f);
    CHECK_FALSE(s.extrapolated);
  }
}

TEST_CASE("PoseHistory predicts past the newest pose at constant velocity, then holds") {
  auto history = std::make_unique<vt::PoseHistory>();
  for (int i = 0; i < 5; ++i) history->publish(handAt(truePalm(i * 16 * kMs), i * 16 * kMs));
  const std::int64_t newest = 64 * kMs;
  vt::PoseSamplingConfig config = mode(vt::PoseSampling::Predict);
  config.maxPrediction_ns = 20 * kMs;
  const vt::PoseSample ahead = history->sample(newest + 10 * kMs, config);
  REQUIRE(ahead.pose.valid);
  CHECK(ahead.extrapolated);
  CHECK(glm::length(palm(ahead) - truePalm(newest + 10 * kMs)) < 1e-6f);
  // Beyond the horizon the prediction stops where the horizon ends.
  const vt::PoseSample far = history->sample(newest + 50 * kMs, config);
  CHECK(glm::length(palm(far) - truePalm(newest + 20 * kMs)) < 1e-6f);
  // Interpolate mode never extrapolates: it holds the newest.
  const vt::PoseSample held = history->sample(newest + 50 * kMs, mode(vt::PoseSampling::Interpolate));
  CHECK(glm::length(palm(held) - truePalm(newest)) < 1e-6f);
}

TEST_CASE("PoseHistory Latest mode is the newest pose whatever the time") {
  auto history = std::make_unique<vt::PoseHistory>();
  for (int i = 0; i < 3; ++i) history->publish(handAt(truePalm(i * 10 * kMs), i * 10 * kMs));
  const vt::PoseSample s = history->sample(5 * kMs, mode(vt::PoseSampling::Latest));
  CHECK(glm::length(palm(s) - truePalm(20 * kMs)) < 1e-6f);
}

TEST_CASE("PoseHistory measures the pose interval and bounds prediction by it") {
  auto history = std::make_unique<vt::PoseHistory>();
  for (int i = 0; i <= 10; ++i) history->publish(handAt(truePalm(i * 5 * kMs), i * 5 * kMs));
  CHECK(history->interval_ns() == 5 * kMs);
  // 200 Hz poses: prediction reaches 2 x 5 ms + 20 ms past the newest, then holds.
  const vt::PoseSample s = history->sample(50 * kMs + 100 * kMs, mode(vt::PoseSampling::Predict));
  CHECK(glm::length(palm(s) - truePalm(50 * kMs + 30 * kMs)) < 1e-6f);
}

TEST_CASE("PoseHistory keeps the newest poses across wrap-around and holds the oldest before them") {
  auto history = std::make_unique<vt::PoseHistory>();
  const int total = 5 * int(vt::PoseHistory::kCapacity) + 3;
  for (int i = 0; i < total; ++i) history->publish(handAt(truePalm(i * kMs), i * kMs));
  CHECK(history->published() == std::uint64_t(total));
  for (int back = 1; back < int(vt::PoseHistory::kCapacity) - 2; back += 7) {
    const std::int64_t at = std::int64_t(total - 1 - back) * kMs + kMs / 2;
    const vt::PoseSample s = history->sample(at, mode(vt::PoseSampling::Predict));
    REQUIRE(s.pose.valid);
    CHECK(glm::length(palm(s) - truePalm(at)) < 1e-6f);
  }
  // Older than the stored window: the oldest stored pose (never a stale or overwritten slot).
  const vt::PoseSample old = history->sample(0, mode(vt::PoseSampling::Predict));
  const std::int64_t oldest = std::int64_t(total - int(vt::PoseHistory::kCapacity) + 1) * kMs;
  CHECK(glm::length(palm(old) - truePalm(oldest)) < 1e-6f);
}

TEST_CASE("PoseHistory refuses out-of-order stamps and takes the later of equal stamps") {
  auto history = std::make_unique<vt::PoseHistory>();
  REQUIRE(history->publish(handAt({0, 0, 0}, 10 * kMs)));
  REQUIRE(history->publish(handAt({0.001f, 0, 0}, 20 * kMs)));
  CHECK_FALSE(history->publish(handAt({0.5f, 0, 0}, 15 * kMs)));
  CHECK(history->rejected() == 1);
  CHECK(history->published() == 2);
  REQUIRE(history->publish(handAt({0.002f, 0, 0}, 20 * kMs)));
  const vt::PoseSample s = history->sample(20 * kMs, mode(vt::PoseSampling::Predict));
  REQUIRE(s.pose.valid);
  CHECK(palm(s).x == Approx(0.002f));
  const vt::PoseSample mid = history->sample(15 * kMs, mode(vt::PoseSampling::Predict));
  CHECK(std::isfinite(palm(mid).x));
  CHECK(palm(mid).x == Approx(0.0005f));
  // Past two equal stamps the velocity comes from the pose before them (no division by zero):
  // 2 mm in 10 ms, continued 10 ms.
  const vt::PoseSample ahead = history->sample(30 * kMs, mode(vt::PoseSampling::Predict));
  CHECK(palm(ahead).x == Approx(0.004f));
}

TEST_CASE("PoseHistory predicts with a velocity over at least half a millisecond") {
  // A hand at rest tracked at 90 Hz, whose source published twice for one frame, 1 us apart,
  // the second a rounding (0.1 um) off: predicting 2 ms ahead must not make 0.2 mm of that.
  auto history = std::make_unique<vt::PoseHistory>();
  const glm::vec3 rest{0.03f, 0.005f, 0.0f};
  for (int i = 0; i < 4; ++i) history->publish(handAt(rest, i * 11 * kMs));
  const std::int64_t twin = 33 * kMs + 1000;
  history->publish(handAt(rest + glm::vec3(1e-7f, 0.0f, 0.0f), twin));
  const vt::PoseSample ahead = history->sample(twin + 2 * kMs, mode(vt::PoseSampling::Predict));
  REQUIRE(ahead.extrapolated);
  CHECK(glm::length(palm(ahead) - rest) < 1e-6f);
  // A real motion is still predicted, over the span to the pose before the twins.
  auto moving = std::make_unique<vt::PoseHistory>();
  for (int i = 0; i < 4; ++i) moving->publish(handAt(truePalm(i * 11 * kMs), i * 11 * kMs));
  moving->publish(handAt(truePalm(33 * kMs + 1000), 33 * kMs + 1000));
  const vt::PoseSample predicted = moving->sample(40 * kMs, mode(vt::PoseSampling::Predict));
  CHECK(glm::length(palm(predicted) - truePalm(40 * kMs)) < 1e-6f);
}

TEST_CASE("PoseHistory never blends across a teleport, a reset or a gap") {
  auto history = std::make_unique<vt::PoseHistory>();
  history->publish(handAt({0, 0, 0}, 0));
  history->publish(handAt({0.001f, 0, 0}, 10 * kMs));
  const std::uint32_t before = history->sample(10 * kMs, mode(vt::PoseSampling::Predict)).segment;

  SECTION("a jump faster than a hand moves") {
    history->publish(handAt({0.2f, 0, 0}, 20 * kMs));  // 20 m/s
  }
  SECTION("a reset the source flags") {
    history->publish(handAt({0.002f, 0, 0}, 20 * kMs), true);
  }
  SECTION("a pause longer than the gap limit") {
    history->publish(handAt({0.0011f, 0, 0}, 20 * kMs + 600 * kMs));
  }
  const vt::PoseSample newest = history->sample(history->interval_ns() + 10'000 * kMs, vt::PoseSamplingConfig{.timeout_ns = 0});
  CHECK(newest.segment != before);
  // Between the two poses around the jump, the older holds: no sweep along the jump.
  const vt::PoseSample mid = history->sample(15 * kMs, mode(vt::PoseSampling::Predict));
  CHECK(mid.segment == before);
  CHECK(palm(mid).x == Approx(0.001f));
  // And no prediction from a velocity measured across the jump.
  vt::PoseSamplingConfig predict = mode(vt::PoseSampling::Predict);
  predict.timeout_ns = 0;
  vt::HandPose last;
  REQUIRE(history->newest(last));
  const vt::PoseSample ahead = history->sample(last.t_ns + 5 * kMs, predict);
  CHECK(palm(ahead).x == Approx(last.at(vt::HandJoint::Palm).x));
}

TEST_CASE("PoseHistory goes silent after the timeout and on tracking loss") {
  auto history = std::make_unique<vt::PoseHistory>();
  vt::PoseSamplingConfig config = mode(vt::PoseSampling::Predict);
  config.timeout_ns = 50 * kMs;
  CHECK_FALSE(history->sample(0, config).pose.valid);  // nothing yet
  history->publish(handAt({0, 0, 0}, 0));
  history->publish(handAt({0.001f, 0, 0}, 10 * kMs));
  CHECK(history->sample(60 * kMs, config).pose.valid);
  CHECK_FALSE(history->sample(61 * kMs, config).pose.valid);
  vt::HandPose lost = handAt({0.001f, 0, 0}, 20 * kMs);
  lost.valid = false;
  history->publish(lost);
  CHECK_FALSE(history->sample(25 * kMs, config).pose.valid);
  // Before the loss the hand was still there.
  CHECK(history->sample(15 * kMs, config).pose.valid);
}

TEST_CASE("PoseHistory readers never see a torn or blended-across-writes pose under a concurrent writer") {
  auto history = std::make_unique<vt::PoseHistory>();
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (std::int64_t i = 0; i < 50'000; ++i) history->publish(handAt(truePalm(i * kMs), i * kMs));
    done = true;
  });
  std::uint64_t checked = 0, torn = 0, offPath = 0, tooOld = 0;
  while (!done) {
    const std::uint64_t n = history->published();
    if (n < 4) continue;
    const std::int64_t at = std::int64_t(n - 3) * kMs + kMs / 3;
    const vt::PoseSample s = history->sample(at, vt::PoseSamplingConfig{.timeout_ns = 0});
    if (!s.pose.valid) continue;  // lapped by the writer: allowed, and rare
    // Every joint moved by the same offset: the pose is one consistent hand.
    const glm::vec3 offset = palm(s) - handAt({0, 0, 0}, 0).at(vt::HandJoint::Palm);
    const glm::vec3 tip = s.pose.at(vt::HandJoint::IndexTip) - handAt({0, 0, 0}, 0).at(vt::HandJoint::IndexTip);
    torn += glm::length(offset - tip) < 1e-5f ? 0 : 1;
    // On the true path, at or after the asked time (later only when the writer lapped the
    // asked time out of the history while this reader was descheduled: the oldest is held).
    const auto described_ns = std::int64_t(double(offset.x) / double(kVelocity_mps.x) * 1e9);
    offPath += glm::length(offset - truePalm(described_ns)) < 2e-5f ? 0 : 1;
    tooOld += described_ns >= at - 100'000 ? 0 : 1;  // float positions: ~1 us of travel
    ++checked;
  }
  writer.join();
  CHECK(checked > 0);
  CHECK(torn == 0);
  CHECK(offPath == 0);
  CHECK(tooOld == 0);
}
