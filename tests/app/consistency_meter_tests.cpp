// The consistency meter against synthetic cases whose answer is known: a display that shows the
// hand a known time before or after what the actuators play, a loop that freezes, a felt
// contact that runs on after the drawn hand stopped.
#include <catch2/catch.hpp>

#include "modes/consistency_meter.hpp"
#include "test_support.hpp"

using namespace vt;

namespace {

using vt::test::kMs;
constexpr double kSpeed_mps = 0.1;

// One index contact point; the tip slides along x at kSpeed_mps from t = 100 ms on (at rest
// before), stopping at `stop_ns` (0: never).
std::vector<haptics::ContactPoint> indexOnly() { return {haptics::ContactPoint{HandJoint::IndexTip, 0.008f}}; }

float tipX(std::int64_t t_ns, std::int64_t stop_ns) {
  const std::int64_t moving_ns = std::max<std::int64_t>(0, (stop_ns > 0 ? std::min(t_ns, stop_ns) : t_ns) - 100 * kMs);
  return float(kSpeed_mps * double(moving_ns) * 1e-9);
}

HandPose pose(std::int64_t t_ns, std::int64_t stop_ns) {
  HandPose p;
  p.t_ns = t_ns;
  p.valid = true;
  p.position[std::size_t(HandJoint::IndexTip)] = {tipX(t_ns, stop_ns), 0.0f, 0.0f};
  return p;
}

// A session of `seconds`: input at 1 kHz, ticks at 1 kHz rendering the hand `feltLead_ns` after
// the tick (what a loop with that hand time plays), frames at 50 Hz showing the hand
// `displayLag_ns` before their display time. `freezeFrom/To`: ticks in between repeat the hand.
app::ConsistencyReport run(std::int64_t feltLatency_ns, std::int64_t handLead_ns, std::int64_t displayLag_ns,
                           std::int64_t stop_ns = 0, std::int64_t freezeFrom_ns = 0, std::int64_t freezeTo_ns = 0,
                           std::int64_t overshoot_ns = 0) {
  app::ConsistencyMeter meter(indexOnly(), kMs);
  meter.setFeltLatency(feltLatency_ns);
  std::int64_t frozenHand_ns = 0;
  for (std::int64_t t = kMs; t <= 2000 * kMs; t += kMs) {
    meter.addInput(pose(t, stop_ns));
    const std::int64_t tick = t - 100 * kMs;  // ticks trail the input, as a loop rendering the past does
    if (tick <= 0) continue;
    std::int64_t hand = tick + handLead_ns;
    if (tick >= freezeFrom_ns && tick < freezeTo_ns) hand = frozenHand_ns ? frozenHand_ns : (frozenHand_ns = hand);
    haptics::ContactTrace trace;
    trace.t_ns = tick;
    trace.inContact = true;
    trace.pose_t_ns = hand;
    // Past the stop the felt contact runs on at the same speed for `overshoot_ns` and comes back
    // as fast (a bad predictor).
    const std::int64_t past = stop_ns > 0 ? std::max<std::int64_t>(0, hand - stop_ns) : 0;
    const std::int64_t running = std::max<std::int64_t>(0, std::min(past, 2 * overshoot_ns - past));
    trace.tip_m = {tipX(hand, stop_ns) + float(kSpeed_mps * double(running) * 1e-9), 0.0f, 0.0f};
    meter.addTrace(trace);
    if (tick % (20 * kMs) == 0) {
      app::DrawnFrame frame;
      frame.display_t_ns = tick + feltLatency_ns;  // shown when this tick's output is felt
      frame.hand_t_ns = frame.display_t_ns - displayLag_ns;
      frame.tip_m[0] = pose(frame.hand_t_ns, stop_ns).at(HandJoint::IndexTip);
      meter.addFrame(frame);
    }
  }
  return meter.report();
}

// A hand whose tip goes along x at kSpeed_mps, `path_m(t)`, read by an input every
// `inputPeriod_ns` (1 ms: a mouse; 11 ms: a 90 Hz tracker); the loop's felt tip and the drawn tip
// are interpolated between those samples (as the pose history does), 175 ms behind the input,
// frames at 50 Hz, felt 5 ms after their tick and shown then.
app::ConsistencyReport sampledSession(float (*path_m)(std::int64_t), std::int64_t inputPeriod_ns) {
  auto sampled = [&](std::int64_t t_ns) {
    const std::int64_t before = t_ns / inputPeriod_ns * inputPeriod_ns;
    const float s = float(double(t_ns - before) / double(inputPeriod_ns));
    return path_m(before) + (path_m(before + inputPeriod_ns) - path_m(before)) * s;
  };
  app::ConsistencyMeter meter(indexOnly(), kMs);
  meter.setFeltLatency(5 * kMs);
  for (std::int64_t t = kMs; t <= 2000 * kMs; t += kMs) {
    if (t % inputPeriod_ns == 0) {
      HandPose p;
      p.t_ns = t;
      p.valid = true;
      p.position[std::size_t(HandJoint::IndexTip)] = {path_m(t), 0.0f, 0.0f};
      meter.addInput(p);
    }
    const std::int64_t tick = t - 100 * kMs;
    if (tick <= 0) continue;
    haptics::ContactTrace trace;
    trace.t_ns = tick;
    trace.inContact = true;
    trace.pose_t_ns = tick - 75 * kMs;
    trace.tip_m = {sampled(trace.pose_t_ns), 0.0f, 0.0f};
    meter.addTrace(trace);
    if (tick % (20 * kMs) == 0) {
      app::DrawnFrame frame;
      frame.display_t_ns = tick + 5 * kMs;
      frame.hand_t_ns = trace.pose_t_ns;
      frame.tip_m[0] = trace.tip_m;
      meter.addFrame(frame);
    }
  }
  return meter.report();
}

// Slides from 100 ms on; at 1 s turns back at once (no rest).
float reversal(std::int64_t t_ns) {
  const std::int64_t turn_ns = 1000 * kMs;
  return tipX(std::min(t_ns, turn_ns), 0) - tipX(std::max(t_ns, turn_ns) - turn_ns + 100 * kMs, 0);
}

// Slides from 100 ms on, rests 150 ms at 1 s, slides on.
float shortRest(std::int64_t t_ns) {
  const std::int64_t rest_ns = 1000 * kMs, rested_ns = 150 * kMs;
  return tipX(t_ns < rest_ns ? t_ns : std::max(rest_ns, t_ns - rested_ns), 0);
}

}  // namespace

TEST_CASE("The consistency meter reports no offset when felt and seen agree", "[app][consistency]") {
  // Felt 5 ms after its tick, the display 80 ms behind: the loop renders tick + 5 - 80 ms.
  const app::ConsistencyReport r = run(5 * kMs, 5 * kMs - 80 * kMs, 80 * kMs);
  REQUIRE(r.framesCompared > 50);
  CHECK(r.offset_ms.p99 < 0.01);
  CHECK(r.offset_mm.p99 < 0.001);
  CHECK(r.frozenMovingPct == 0.0);
}

TEST_CASE("The consistency meter reports a known temporal offset with its sign", "[app][consistency]") {
  // The loop renders 12 ms later than the display shows: touch leads sight by 12 ms, 1.2 mm at 0.1 m/s.
  const app::ConsistencyReport leads = run(5 * kMs, 5 * kMs - 80 * kMs + 12 * kMs, 80 * kMs);
  CHECK(leads.offset_ms.signedP99 == Approx(12.0).margin(0.01));
  CHECK(leads.offset_ms.p99 == Approx(12.0).margin(0.01));
  CHECK(leads.offset_mm.p99 == Approx(1.2).margin(0.01));
  // Ignoring the display lag altogether: touch leads by the whole lag.
  const app::ConsistencyReport unaligned = run(5 * kMs, 5 * kMs, 80 * kMs);
  CHECK(unaligned.offset_ms.signedP99 == Approx(80.0).margin(0.01));
  // Lagging sight is negative.
  const app::ConsistencyReport lags = run(5 * kMs, 5 * kMs - 90 * kMs, 80 * kMs);
  CHECK(lags.offset_ms.p50 == Approx(10.0).margin(0.01));
  CHECK(lags.offset_ms.signedP99 < 0.0);
}

TEST_CASE("The consistency meter counts a frozen run while the hand moves", "[app][consistency]") {
  // 30 ticks repeat the same hand mid-slide: 29 repeats, a 29 ms run.
  const app::ConsistencyReport r = run(5 * kMs, 5 * kMs - 80 * kMs, 80 * kMs, 0, 800 * kMs, 830 * kMs);
  CHECK(r.frozenTicks == 29);
  CHECK(r.frozenRunMax_ms == Approx(29.0).margin(0.01));
  CHECK(r.frozenMovingPct > 0.0);
}

TEST_CASE("The consistency meter measures how far and long texture runs on after a stop", "[app][consistency]") {
  const std::int64_t stop = 1200 * kMs;
  const app::ConsistencyReport clean = run(5 * kMs, 5 * kMs - 80 * kMs, 80 * kMs, stop);
  CHECK(clean.stops >= 1);
  CHECK(clean.stopOvershoot_mm == 0.0);
  // The felt contact runs on 40 ms past the stop (4 mm at 0.1 m/s) and is back 80 ms after it;
  // the first frame showing the stop draws the hand 5 ms after it, so 74.5 ms after that frame.
  const app::ConsistencyReport runsOn = run(5 * kMs, 5 * kMs - 80 * kMs, 80 * kMs, stop, 0, 0, 40 * kMs);
  CHECK(runsOn.stops >= 1);
  CHECK(runsOn.stopOvershoot_mm == Approx(4.0).margin(0.2));
  CHECK(runsOn.stopOvershoot_ms == Approx(74.5).margin(1.0));
  // The loop and the display show the hand 50 ms after the newest input (a headset's prediction):
  // the input shows the stop 100 ms after it happened, once the ticks that ran on are made and
  // the frame that showed the stop is drawn; they count all the same.
  const app::ConsistencyReport ahead = run(5 * kMs, 150 * kMs, -145 * kMs, stop, 0, 0, 40 * kMs);
  CHECK(ahead.stops >= 1);
  CHECK(ahead.stopOvershoot_mm == Approx(4.0).margin(0.2));
  CHECK(ahead.stopOvershoot_ms == Approx(69.5).margin(1.0));  // that frame draws the hand 10 ms after the stop
}

TEST_CASE("The consistency meter does not take a reversal for a stop", "[app][consistency]") {
  // At the turn the tip passes the same point twice, 100 ms apart: not a rest.
  const app::ConsistencyReport r = sampledSession(reversal, kMs);
  CHECK(r.stops == 0);
  CHECK(r.stopOvershoot_ms == 0.0);
}

TEST_CASE("The consistency meter ends a stop where the hand moves on, between two tracker samples", "[app][consistency]") {
  // A 150 ms rest, shorter than the 300 ms followed: the felt tip leaves with the hand, between the
  // last sample at rest and the first one away; that is the next move, not texture running on.
  const app::ConsistencyReport tracker = sampledSession(shortRest, 11 * kMs);
  CHECK(tracker.stops == 1);
  CHECK(tracker.stopOvershoot_ms == 0.0);
  CHECK(tracker.stopOvershoot_mm == 0.0);
  const app::ConsistencyReport mouse = sampledSession(shortRest, kMs);
  CHECK(mouse.stops == 1);
  CHECK(mouse.stopOvershoot_mm == 0.0);
}
