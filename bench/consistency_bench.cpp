// `vt_bench consistency`: is the texture felt where and when the finger is seen? The index
// fingertip slides at constant speed across a stripe grating of known spatial period (texture
// model) while poses reach the touch pipeline the way each input path delivers them; the
// output waveform and the contact traces are compared with the true fingertip.
//   scripted  a pose every tick, stamped exactly (the reference)
//   desktop   poses at 60 Hz with frame-time jitter, stamped with their input time
//   xr        through xrsim: the frame loop locates the hand for each predicted display time
//             (72 Hz frames), the runtime's tracker running at 72 Hz or 30 Hz
//   net       a client with desktop input sends poses at the block rate over loopback to a
//             server pipeline (0 % and 5 % loss); the server's output is measured
// Each path runs in each pose-sampling mode (latest, interpolate, predict) at 0.05, 0.1 and
// 0.2 m/s. Constant speeds make interpolation and constant-velocity prediction exact by
// construction, so the pose history is also driven along motions where a wrong model shows:
//   reach   a minimum-jerk reach of 8 cm in 0.5 s that stops (acceleration, deceleration)
//   reverse a reach that turns back without stopping (the velocity flips)
// on the scripted (1 kHz) and desktop (60 Hz) inputs: the contact point's error against the
// true fingertip at the tick's time and how far it runs past the stop. The measurement of the
// running program is `vt_bench live` (tools/live). Figures: docs/PERFORMANCE.md ("Spatial-temporal consistency").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <thread>

#include <nlohmann/json.hpp>

#include "bench.hpp"
#include "modes/touch_pipeline.hpp"
#include "ui/canvas.hpp"
#include "vt/scene/image.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/log.hpp"
#include "vt/haptics/signal_analysis.hpp"
#include "vt/net/server.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/scene/demo_scene.hpp"
#include "vt/xr/headset.hpp"

namespace vt::bench {
namespace {

constexpr double kGratingPeriod_m = 0.002;
constexpr float kPlate_m = 0.2f;
constexpr double kSampleRate_hz = 8000.0;
constexpr std::int64_t kMs = 1'000'000;
// The index tip starts 2 cm inside the plate's left edge, 2 mm deep (8 mm radius).
const glm::vec3 kStart{-0.08f, 0.006f, 0.0f};
constexpr double kOnPlate_m = 0.17;  // a slide stays this far on the plate (1 cm before its edge)
constexpr double kSkip_s = 0.1;  // onset ramps, interpolation warm-up
constexpr double kXrRest_s = 3.0;  // xr: the scripted hand rests this long before sliding

app::LoadedScene gratingScene() {
  auto scene = std::make_shared<const Scene>(makeGratingPlate(kPlate_m, float(kGratingPeriod_m)));
  return {scene, haptics::makeHapticScene(scene), "stripe grating, 2 mm period"};
}

glm::vec3 trueTip(double speed_mps, double t_s) { return kStart + glm::vec3(float(speed_mps * t_s), 0.0f, 0.0f); }

// Every joint far above the plate except the index tip.
HandPose handWithTip(glm::vec3 tip, std::int64_t t_ns) {
  HandPose pose;
  pose.t_ns = t_ns;
  pose.valid = true;
  for (auto& p : pose.position) p = glm::vec3(0.0f, 0.5f, 0.0f);
  for (auto& q : pose.orientation) q = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  for (auto& r : pose.radius_m) r = kDefaultFingertipRadius_m;
  pose.position[std::size_t(HandJoint::IndexTip)] = tip;
  return pose;
}

// What one run produced: the index actuator's samples as played (uniform 8 kHz from the
// first frame's block start) and the index contact's traces; times relative to the slide start.
struct Recording {
  std::vector<float> wave;
  double waveStart_s = 0.0;
  std::vector<haptics::ContactTrace> traces;
  std::int64_t slideStart_ns = 0;
  double speed_mps = 0.0;
  double duration_s = 0.0;
};

void collect(app::TouchPipeline& pipeline, Recording& out) {
  const std::size_t index = 1;  // fiveFingertips: contact 1 drives actuator 1
  pipeline.onFrame([&out, index](const haptics::ActuatorFrame& f) {
    if (f.blockLength == 0) return;
    if (out.wave.empty()) {
      out.waveStart_s = double(f.t_ns - out.slideStart_ns) * 1e-9 - double(f.blockLength) / kSampleRate_hz;
    }
    for (int k = 0; k < f.blockLength; ++k) out.wave.push_back(f.block[index][std::size_t(k)]);
  });
  pipeline.onTrace([&out, index](const haptics::ContactTrace& t) {
    if (t.contact == index) out.traces.push_back(t);
  });
}

app::TouchPipelineSpec steppedSpec(PoseSampling mode, const Clock* clock) {
  app::TouchPipelineSpec spec;
  spec.haptic.model = haptics::TactileModelKind::TextureWaveform;
  spec.haptic.sampling = mode;
  spec.sinks.glove = "none";
  spec.drive = app::TouchDrive::Stepped;
  spec.clock = clock;
  return spec;
}

// Scripted and desktop: poses reach the history at `posesAt` times (stamped with the time
// they describe, published then), ticks run at 1 kHz on a manual clock.
Recording runStepped(const app::LoadedScene& scene, PoseSampling mode, double speed, double seconds,
                     const std::vector<std::int64_t>& poseTimes_ns) {
  ManualClock clock;
  app::TouchPipeline pipeline(scene, steppedSpec(mode, &clock));
  Recording rec{.slideStart_ns = 0, .speed_mps = speed, .duration_s = seconds};
  collect(pipeline, rec);
  std::size_t next = 0;
  for (std::int64_t t = 0; t <= std::int64_t(seconds * 1e9); t += kMs) {
    while (next < poseTimes_ns.size() && poseTimes_ns[next] <= t) {
      const std::int64_t at = poseTimes_ns[next++];
      pipeline.publishPose(handWithTip(trueTip(speed, double(at) * 1e-9), at));
    }
    clock.set(t);
    pipeline.tick(t);
    pipeline.drain();
  }
  return rec;
}

// Motions with acceleration, a stop and a turn: the true fingertip at t (s after the start).
enum class Shape { Reach, Reverse };
constexpr double kShapeDuration_s = 0.9;

glm::vec3 shapedTip(Shape shape, double t_s) {
  auto minimumJerk = [](double tau) {
    tau = std::clamp(tau, 0.0, 1.0);
    return tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau);
  };
  double x = 0.0;
  if (shape == Shape::Reach) {
    x = 0.08 * minimumJerk(t_s / 0.5);  // 8 cm in 0.5 s (peak 0.3 m/s), then still
  } else {
    // Out 6 cm and back 4 cm, the second move starting as the first ends (velocity through 0 at the turn).
    x = t_s < 0.4 ? 0.06 * minimumJerk(t_s / 0.4) : 0.06 - 0.04 * minimumJerk((t_s - 0.4) / 0.3);
  }
  return kStart + glm::vec3(float(x), 0.0f, 0.0f);
}

struct ShapeFigures {
  double errorP99_mm = 0.0;      // |contact sphere centre - true tip| at each tick, 99th percentile
  double overshoot_mm = 0.0;     // how far the contact point ran past where the hand stopped
};

// Poses at `poseTimes_ns` (stamped with their time) along the shape, ticks at 1 kHz.
ShapeFigures runShape(const app::LoadedScene& scene, PoseSampling mode, Shape shape,
                      const std::vector<std::int64_t>& poseTimes_ns) {
  ManualClock clock;
  app::TouchPipeline pipeline(scene, steppedSpec(mode, &clock));
  std::vector<haptics::ContactTrace> traces;
  pipeline.onTrace([&traces](const haptics::ContactTrace& t) {
    if (t.contact == 1) traces.push_back(t);
  });
  std::size_t next = 0;
  for (std::int64_t t = 0; t <= std::int64_t(kShapeDuration_s * 1e9); t += kMs) {
    while (next < poseTimes_ns.size() && poseTimes_ns[next] <= t) {
      const std::int64_t at = poseTimes_ns[next++];
      pipeline.publishPose(handWithTip(shapedTip(shape, double(at) * 1e-9), at));
    }
    clock.set(t);
    pipeline.tick(t);
    pipeline.drain();
  }
  ShapeFigures f;
  std::vector<double> errors;
  const double stop_x = double(shapedTip(shape, kShapeDuration_s).x);
  for (const haptics::ContactTrace& t : traces) {
    const double t_s = double(t.t_ns) * 1e-9;
    if (t_s < kSkip_s || !t.inContact) continue;
    errors.push_back(1000.0 * double(glm::length(t.tip_m - shapedTip(shape, t_s))));
    if (shape == Shape::Reach) f.overshoot_mm = std::max(f.overshoot_mm, 1000.0 * (double(t.tip_m.x) - stop_x));
    else if (t_s < 0.4 + 0.05) f.overshoot_mm = std::max(f.overshoot_mm, 1000.0 * (double(t.tip_m.x) - double(shapedTip(shape, 0.4).x)));
  }
  std::sort(errors.begin(), errors.end());
  if (!errors.empty()) f.errorP99_mm = errors[std::size_t(0.99 * double(errors.size() - 1))];
  return f;
}

std::vector<std::int64_t> scriptedTimes(double seconds) {
  std::vector<std::int64_t> t;
  for (std::int64_t at = 0; at <= std::int64_t(seconds * 1e9); at += kMs) t.push_back(at);
  return t;
}

// 60 Hz frames whose start times jitter (a desktop compositor and a loaded renderer).
std::vector<std::int64_t> desktopTimes(double seconds, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> jitter(0.0, 2.0e6);
  std::vector<std::int64_t> t;
  for (int k = 0;; ++k) {
    const auto at = std::int64_t(double(k) * 1e9 / 60.0 + std::clamp(jitter(rng), -6e6, 6e6));
    if (at > std::int64_t(seconds * 1e9)) break;
    if (t.empty() || at > t.back()) t.push_back(std::max<std::int64_t>(at, 0));
  }
  return t;
}

// xr: the real xrsim runtime in non-realtime mode (display times advance one period per frame).
// Each frame locates the hand for its predicted display time T; the pose is available one
// frame period before T (the locate happens at frame start), so ticks run up to T - period.
Recording runXr(const app::LoadedScene& scene, PoseSampling mode, double speed, double seconds, double handRate_hz,
                const std::filesystem::path& work) {
  std::filesystem::create_directories(work);
  xr::HeadsetOptions options;
  options.placeAtHead = false;  // the hand is scripted in stage coordinates around the fixed table
  const glm::vec3 stageOffset(options.T_stage_world[3]);
  auto joints = [&](glm::vec3 tip) {
    nlohmann::json list = nlohmann::json::array();
    const HandPose pose = handWithTip(tip, 0);
    for (int j = 0; j < kHandJointCount; ++j) {
      const glm::vec3 p = pose.position[std::size_t(j)] + stageOffset;
      list.push_back({{"position", {p.x, p.y, p.z}}, {"orientation", {0.0, 0.0, 0.0, 1.0}}, {"radius", 0.008}});
    }
    return list;
  };
  // The hand rests at the start while the pipeline starts (its first frames can come seconds
  // after xrBeginSession on a loaded machine), then slides.
  const double slide_s = seconds + 0.3;
  nlohmann::json script = {{"keyframes", nlohmann::json::array({
      {{"t", 0.0}, {"right", {{"tracked", true}, {"joints", joints(trueTip(speed, 0.0))}}}},
      {{"t", kXrRest_s}, {"right", {{"tracked", true}, {"joints", joints(trueTip(speed, 0.0))}}}},
      {{"t", kXrRest_s + slide_s}, {"right", {{"tracked", true}, {"joints", joints(trueTip(speed, slide_s))}}}},
  })}};
  std::ofstream(work / "script.json") << script.dump();
  setenv("XRSIM_SCRIPT", (work / "script.json").c_str(), 1);
  setenv("XRSIM_HAND_RATE_HZ", std::to_string(handRate_hz).c_str(), 1);
  setenv("XRSIM_FRAME_RATE_HZ", "72", 1);
  setenv("XRSIM_WIDTH", "64", 1);
  setenv("XRSIM_HEIGHT", "64", 1);
  setenv("XRSIM_REALTIME", "1", 1);  // XrTime on the wall clock: poses stamped at display time
  const int frameBudget = int((kXrRest_s + slide_s) * 72.0) + 200;  // the rest, the slide, start-up
  setenv("XRSIM_FRAMES", std::to_string(frameBudget).c_str(), 1);
  setenv("XR_RUNTIME_JSON", VT_XRSIM_MANIFEST, 0);

  ManualClock clock;
  app::TouchPipeline pipeline(scene, steppedSpec(mode, &clock));
  options.handOutputs[1] = &pipeline.poses();
  auto opened = xr::Headset::open(options);
  if (!opened.headset) fail("consistency: xrsim: ", opened.message);
  xr::Headset& headset = *opened.headset;
  Recording rec{.speed_mps = speed, .duration_s = seconds};
  collect(pipeline, rec);
  std::int64_t tick = -1;
  const std::int64_t period_ns = std::int64_t(1e9 / 72.0);
  for (int frames = 0; frames < frameBudget;) {
    const xr::SessionPhase phase = headset.pollEvents();
    if (phase == xr::SessionPhase::Exiting || phase == xr::SessionPhase::LossPending) break;
    if (phase != xr::SessionPhase::Running) continue;
    headset.frame([](int, const CameraView&, renderer::RenderTarget&) {});
    ++frames;
    HandPose newest;
    if (!pipeline.poses().newest(newest) || !newest.valid) continue;
    const glm::vec3 tip = newest.at(HandJoint::IndexTip);
    const double into_s = double(tip.x - kStart.x) / speed;
    if (rec.slideStart_ns == 0) {
      // Until the pipeline is visible the runtime tracks no joints (the controller poses the hand).
      if (std::abs(tip.y - kStart.y) > 1e-4f || std::abs(tip.z - kStart.z) > 1e-4f) continue;
      if (into_s < 1e-4) continue;  // still resting: the slide has not begun
      // Where the tip is gives when the slide began (the runtime answers for the display time).
      if (into_s > 0.2) fail("consistency: xrsim's first frames came too late (", into_s, " s into the slide)");
      rec.slideStart_ns = newest.t_ns - std::int64_t(into_s * 1e9);
      tick = rec.slideStart_ns;
    }
    for (; tick <= newest.t_ns - period_ns; tick += kMs) {
      clock.set(tick);
      pipeline.tick(tick);
    }
    pipeline.drain();
    if (double(tick - rec.slideStart_ns) * 1e-9 > seconds) break;
  }
  headset.requestExit();
  for (int i = 0; i < 100 && headset.pollEvents() != xr::SessionPhase::Exiting; ++i) {
  }
  return rec;
}

// net: a desktop-input client pipeline over loopback to a server pipeline stepped per pose.
Recording runNet(const app::LoadedScene& scene, PoseSampling mode, double speed, double seconds, double loss) {
  app::TouchPipelineSpec serverSpec = steppedSpec(mode, &SteadyClock::instance());
  serverSpec.haptic.rate_hz = 250.0f;  // one 32-sample block per pose, as `vtouching serve`
  serverSpec.drive = app::TouchDrive::Served;
  net::ServerConfig serverConfig;
  serverConfig.bind = net::parseEndpoint("127.0.0.1:0");
  serverConfig.sceneDigest = tactileDigest(*scene.scene);
  serverConfig.impairment.loss = loss;
  serverSpec.served = serverConfig;
  app::TouchPipeline server(scene, serverSpec);
  net::Server& network = *server.server();
  Recording rec{.speed_mps = speed, .duration_s = seconds};
  collect(server, rec);

  app::TouchPipelineSpec clientSpec;
  clientSpec.haptic.sampling = mode;
  clientSpec.sinks.glove = "none";
  clientSpec.drive = app::TouchDrive::Remote;
  net::ClientConfig clientConfig;
  clientConfig.server = network.endpoint();
  clientConfig.codecs = {haptics::CodecId::RawFloat32};
  clientConfig.impairment.loss = loss;
  clientSpec.remote = clientConfig;
  app::TouchPipeline client(scene, clientSpec);
  const Clock& clock = SteadyClock::instance();
  rec.slideStart_ns = clock.now_ns();
  for (const std::int64_t at : desktopTimes(seconds, 11)) {
    clock.sleepUntil(rec.slideStart_ns + at);
    const std::int64_t now = clock.now_ns();
    client.publishPose(handWithTip(trueTip(speed, double(now - rec.slideStart_ns) * 1e-9), now));
    client.drain();
  }
  client.stop();
  network.stop();
  server.drain();
  return rec;
}

// Figures of one run.
struct Figures {
  // NaN (null in the JSON) when the run produced too little to measure.
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  double freqErrorPct = kNone, gapMs = kNone, uvStepP99 = kNone, onsetP50 = kNone, onsetP99 = kNone,
         positionP99 = kNone;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::size_t(std::round(p * double(v.size() - 1)))];
}

Figures analyse(const Recording& rec) {
  Figures fig;
  const double expected_hz = rec.speed_mps / kGratingPeriod_m;
  // The played waveform inside the contact window.
  const auto first = std::size_t(std::max(0.0, (kSkip_s - rec.waveStart_s) * kSampleRate_hz));
  const auto last = std::min(rec.wave.size(), std::size_t(std::max(0.0, (rec.duration_s - rec.waveStart_s) * kSampleRate_hz)));
  if (last <= first + 1000) return fig;
  const std::vector<float> window(rec.wave.begin() + std::ptrdiff_t(first), rec.wave.begin() + std::ptrdiff_t(last));
  const double measured = haptics::dominantFrequency_hz(window, kSampleRate_hz, 0.5 * expected_hz, 2.0 * expected_hz);
  fig.freqErrorPct = 100.0 * std::abs(measured - expected_hz) / expected_hz;

  // Gaps: runs below 2 % of the window's peak.
  float peak = 0.0f;
  for (float v : window) peak = std::max(peak, std::abs(v));
  std::size_t run = 0, longest = 0;
  for (float v : window) {
    run = std::abs(v) < 0.02f * peak ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  fig.gapMs = 1000.0 * double(longest) / kSampleRate_hz;

  // Onsets: each upward crossing of half the peak after the output was below it, against the
  // nearest true rising edge (x = -0.1 + k * period).
  std::vector<double> offsets;
  for (std::size_t i = first + 1; i < last; ++i) {
    if (!(rec.wave[i - 1] < 0.5f * peak && rec.wave[i] >= 0.5f * peak)) continue;
    const double frac = double(0.5f * peak - rec.wave[i - 1]) / double(rec.wave[i] - rec.wave[i - 1]);
    const double t_s = rec.waveStart_s + (double(i - 1) + frac + 1.0) / kSampleRate_hz;
    const double x = double(kStart.x) + rec.speed_mps * t_s;
    const double edge = -0.1 + std::round((x + 0.1) / kGratingPeriod_m) * kGratingPeriod_m;
    offsets.push_back(1000.0 * (t_s - (edge - double(kStart.x)) / rec.speed_mps));
  }
  fig.onsetP50 = percentile(offsets, 0.5);
  std::vector<double> magnitude;
  for (double o : offsets) magnitude.push_back(std::abs(o));
  fig.onsetP99 = percentile(magnitude, 0.99);

  // UV steps and positions from the traces.
  const double trueStep = rec.speed_mps / double(kPlate_m);  // u per second
  std::vector<double> steps, errors;
  for (std::size_t i = 1; i < rec.traces.size(); ++i) {
    const haptics::ContactTrace& a = rec.traces[i - 1];
    const haptics::ContactTrace& b = rec.traces[i];
    const double t_s = double(b.t_ns - rec.slideStart_ns) * 1e-9;
    if (t_s < kSkip_s || t_s > rec.duration_s || !a.inContact || !b.inContact) continue;
    steps.push_back(std::abs(double(b.u - a.u)) / (trueStep * double(b.t_ns - a.t_ns) * 1e-9));
    errors.push_back(1000.0 * double(glm::length(b.tip_m - trueTip(rec.speed_mps, t_s))));
  }
  fig.uvStepP99 = percentile(steps, 0.99);
  fig.positionP99 = percentile(errors, 0.99);
  return fig;
}

// One slide's output (desktop input at 60 Hz, 0.1 m/s): the waveform over 150 ms and its
// spectrum, the newest pose alone against the default sampling.
void plotSlide(const Recording& latest, const Recording& predicted, const std::string& file) {
  constexpr int kWidth = 1000, kPanel = 260, kMargin = 50;
  ui::Canvas canvas(kWidth, 2 * kPanel + 3 * kMargin, {255, 255, 255, 255});
  const glm::u8vec4 grey{150, 150, 150, 255}, black{30, 30, 30, 255};
  const glm::u8vec4 colors[2] = {{220, 80, 60, 255}, {40, 110, 200, 255}};
  const Recording* runs[2] = {&latest, &predicted};
  const float plotWidth = float(kWidth - 2 * kMargin);
  // Waveform: 150 ms from 0.4 s into the slide, each run in its own half-height lane.
  const float top = float(kMargin);
  canvas.strokeRect({float(kMargin), top}, {float(kWidth - kMargin), top + float(kPanel)}, grey);
  canvas.text({float(kMargin), top - 30.0f}, "index actuator waveform, 0.40-0.55 s of a 0.1 m/s slide over a 2 mm grating (desktop input, 60 Hz)", black);
  for (int r = 0; r < 2; ++r) {
    const Recording& rec = *runs[r];
    const float lane = top + float(kPanel) * (0.25f + 0.5f * float(r));
    const auto first = std::size_t(std::max(0.0, (0.4 - rec.waveStart_s) * kSampleRate_hz));
    const std::size_t count = std::size_t(0.15 * kSampleRate_hz);
    for (std::size_t k = 1; k < count && first + k < rec.wave.size(); ++k) {
      auto at = [&](std::size_t i) {
        return glm::vec2(float(kMargin) + plotWidth * float(i) / float(count), lane - 50.0f * rec.wave[first + i]);
      };
      canvas.line(at(k - 1), at(k), colors[r], 1.5f);
    }
    canvas.text({float(kMargin) + 6.0f, lane - float(kPanel) * 0.22f}, r == 0 ? "latest pose" : "predict (default)", colors[r]);
  }
  // Spectrum 0..300 Hz of 0.1..1.1 s, in dB below each run's peak.
  const float bottom = float(2 * kMargin + kPanel);
  canvas.strokeRect({float(kMargin), bottom}, {float(kWidth - kMargin), bottom + float(kPanel)}, grey);
  canvas.text({float(kMargin), bottom - 30.0f}, "spectrum 0-300 Hz, dB below each run's peak (60 dB shown); the grating gives 50 Hz and its odd harmonics", black);
  for (int r = 0; r < 2; ++r) {
    const Recording& rec = *runs[r];
    const auto first = std::size_t(std::max(0.0, (0.1 - rec.waveStart_s) * kSampleRate_hz));
    const std::size_t count = std::min(rec.wave.size() - std::min(rec.wave.size(), first), std::size_t(kSampleRate_hz));
    const std::span<const float> window(rec.wave.data() + first, count);
    std::vector<double> db;
    for (double f = 1.0; f <= 300.0; f += 1.0) db.push_back(10.0 * std::log10(haptics::spectralPower(window, f, kSampleRate_hz) + 1e-12));
    const double peak = *std::max_element(db.begin(), db.end());
    for (std::size_t i = 1; i < db.size(); ++i) {
      auto at = [&](std::size_t j) {
        const double level = std::clamp((db[j] - peak + 60.0) / 60.0, 0.0, 1.0);
        return glm::vec2(float(kMargin) + plotWidth * float(j) / float(db.size()), bottom + float(kPanel) * float(1.0 - level));
      };
      canvas.line(at(i - 1), at(i), colors[r], 1.5f);
    }
  }
  for (int f = 0; f <= 300; f += 50)
    canvas.text({float(kMargin) + plotWidth * float(f) / 300.0f - 8.0f, bottom + float(kPanel) + 6.0f}, std::to_string(f) + " Hz", black);
  savePng(file, canvas.image());
}

// The goals for the default mode at 0.1 m/s on the deterministic paths (the network
// paths run in real time on a shared machine: reported, not checked).
bool goalsMet(const nlohmann::ordered_json& out) {
  struct Goal {
    const char* figure;
    double limit;
  };
  const Goal goals[] = {{"freq_error_pct", 3.0}, {"gap_ms_max", 2.0}, {"uv_step_ratio_p99", 1.5},
                        {"onset_offset_ms_p99", 5.0}, {"position_error_mm_p99", 0.5}};
  bool met = true;
  for (const char* path : {"scripted", "desktop", "xr72", "xr30"}) {
    for (const Goal& goal : goals) {
      const std::string key = str(path, "_", poseSamplingName(PoseSampling::Predict), "_0.1mps_", goal.figure);
      const double value = out.contains(key) && out[key].is_number() ? out[key].get<double>() : 1e9;
      if (!(std::abs(value) <= goal.limit)) {
        std::fprintf(stderr, "consistency: %s = %.3f misses the goal %.3f\n", key.c_str(), value, goal.limit);
        met = false;
      }
    }
  }
  // A wrong model fails these: the 1 kHz input (the desktop's) through the default sampling
  // along motions that accelerate, stop and turn.
  for (const char* shape : {"reach", "reverse"}) {
    for (const char* figure : {"error_mm_p99", "overshoot_mm"}) {
      const std::string key = str("scripted_predict_", shape, "_", figure);
      const double value = out.contains(key) && out[key].is_number() ? out[key].get<double>() : 1e9;
      if (!(value <= 0.5)) {
        std::fprintf(stderr, "consistency: %s = %.3f misses the goal 0.5\n", key.c_str(), value);
        met = false;
      }
    }
  }
  if (met) std::printf("consistency: every goal met on scripted, desktop, xr72 and xr30 (predict, 0.1 m/s) and on the shaped motions\n");
  return met;
}

}  // namespace

VT_BENCH_SUITE(consistency, "visual-tactile consistency: output frequency, gaps, onsets, positions per input path") {
  log::setLevel(log::Level::Warn);
  const app::LoadedScene scene = gratingScene();
  const double duration_s = options.quick ? 0.6 : 1.2;
  const std::vector<double> speeds = options.quick ? std::vector<double>{0.1} : std::vector<double>{0.05, 0.1, 0.2};
  const std::filesystem::path work = std::filesystem::temp_directory_path() / "vt_bench_consistency";
  nlohmann::ordered_json out;
  Recording plotLatest, plotPredicted;
  for (PoseSampling mode : {PoseSampling::Latest, PoseSampling::Interpolate, PoseSampling::Predict}) {
    for (double speed : speeds) {
      const double seconds = std::min(duration_s, kOnPlate_m / speed);
      struct Path {
        std::string name;
        Recording rec;
      };
      std::vector<Path> paths;
      paths.push_back({"scripted", runStepped(scene, mode, speed, seconds, scriptedTimes(seconds))});
      paths.push_back({"desktop", runStepped(scene, mode, speed, seconds, desktopTimes(seconds, 7))});
      paths.push_back({"xr72", runXr(scene, mode, speed, seconds, 72.0, work)});
      paths.push_back({"xr30", runXr(scene, mode, speed, seconds, 30.0, work)});
      paths.push_back({"net0", runNet(scene, mode, speed, seconds, 0.0)});
      paths.push_back({"net5", runNet(scene, mode, speed, seconds, 0.05)});
      if (!options.plot.empty() && speed == 0.1) (mode == PoseSampling::Latest ? plotLatest : plotPredicted) = paths[1].rec;
      for (const Path& path : paths) {
        const Figures f = analyse(path.rec);
        char prefix[96];
        std::snprintf(prefix, sizeof prefix, "%s_%s_%gmps_", path.name.c_str(), poseSamplingName(mode), speed);
        const std::string p = prefix;
        out[p + "freq_error_pct"] = f.freqErrorPct;
        out[p + "gap_ms_max"] = f.gapMs;
        out[p + "uv_step_ratio_p99"] = f.uvStepP99;
        out[p + "onset_offset_ms_p50"] = f.onsetP50;
        out[p + "onset_offset_ms_p99"] = f.onsetP99;
        out[p + "position_error_mm_p99"] = f.positionP99;
        if (!options.json) {
          std::printf("%-8s %-11s %.2f m/s  freq err %6.2f %%  gap %6.2f ms  uv step p99 %6.2f  onset p50 %6.2f p99 %6.2f ms  "
                      "pos p99 %6.3f mm\n",
                      path.name.c_str(), poseSamplingName(mode), speed, f.freqErrorPct, f.gapMs, f.uvStepP99, f.onsetP50,
                      f.onsetP99, f.positionP99);
          std::fflush(stdout);
        }
      }
    }
  }
  for (PoseSampling mode : {PoseSampling::Latest, PoseSampling::Interpolate, PoseSampling::Predict}) {
    for (const auto& [shapeName, shape] : {std::pair{"reach", Shape::Reach}, std::pair{"reverse", Shape::Reverse}}) {
      for (const auto& [pathName, times] : {std::pair{"scripted", scriptedTimes(kShapeDuration_s)},
                                            std::pair{"desktop", desktopTimes(kShapeDuration_s, 7)}}) {
        const ShapeFigures f = runShape(scene, mode, shape, times);
        const std::string p = str(pathName, "_", poseSamplingName(mode), "_", shapeName, "_");
        out[p + "error_mm_p99"] = f.errorP99_mm;
        out[p + "overshoot_mm"] = f.overshoot_mm;
        if (!options.json)
          std::printf("%-8s %-11s %-8s position error p99 %7.3f mm  overshoot %7.3f mm\n", pathName, poseSamplingName(mode),
                      shapeName, f.errorP99_mm, f.overshoot_mm);
      }
    }
  }
  if (options.json) std::printf("%s\n", out.dump(2).c_str());
  if (!options.plot.empty()) plotSlide(plotLatest, plotPredicted, options.plot);
  return options.check && !goalsMet(out) ? 1 : 0;
}

}  // namespace vt::bench
