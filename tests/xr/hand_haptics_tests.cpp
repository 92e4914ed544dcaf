// Input and haptics through xrsim: a scripted tracked hand slides across a plate, the haptic
// loop renders the contact, the XR haptic sink drives controller vibration that xrsim logs;
// and controller input poses a hand whose index finger curls with the trigger.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <algorithm>
#include <map>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "vt/haptics/frequency_scale.hpp"
#include "vt/haptics/haptic_loop.hpp"
#include "vt/scene/demo_scene.hpp"
#include "vt/xr/haptic_sink.hpp"
#include "xr_fixture.hpp"

using nlohmann::json;

namespace {

json poseJson(const glm::vec3& p, const glm::quat& q, float radius) {
  return {{"position", {p.x, p.y, p.z}}, {"orientation", {q.x, q.y, q.z, q.w}}, {"radius", radius}};
}

// A flat right hand, palm down, index straight, its tip at tip_world (scene coordinates).
vt::HandPose handWithIndexTipAt(const glm::vec3& tip_world) {
  const vt::FingerCurls curls = {0.3f, 0.0f, 0.9f, 0.9f, 0.9f};
  const vt::HandPose probe = vt::poseHand(glm::mat4(1.0f), curls);
  const glm::vec3 offset = tip_world - probe.at(vt::HandJoint::IndexTip);
  return vt::poseHand(glm::translate(glm::mat4(1.0f), offset), curls);
}

json handKeyframe(double t, const vt::HandPose& pose_world, const glm::mat4& T_stage_world) {
  json joints = json::array();
  const glm::quat q_stage_world = glm::quat_cast(glm::mat3(T_stage_world));
  for (int j = 0; j < vt::kHandJointCount; ++j) {
    const glm::vec3 p = glm::vec3(T_stage_world * glm::vec4(pose_world.position[std::size_t(j)], 1.0f));
    joints.push_back(poseJson(p, q_stage_world * pose_world.orientation[std::size_t(j)], 0.008f));
  }
  return {{"t", t}, {"right", {{"joints", joints}}}};
}

/// Pearson correlation of (x, y) pairs.
double pearson(const std::vector<std::pair<double, double>>& pairs) {
  double mx = 0, my = 0;
  for (const auto& [x, y] : pairs) mx += x, my += y;
  mx /= double(pairs.size());
  my /= double(pairs.size());
  double sxy = 0, sxx = 0, syy = 0;
  for (const auto& [x, y] : pairs) sxy += (x - mx) * (y - my), sxx += (x - mx) * (x - mx), syy += (y - my) * (y - my);
  return sxy / std::sqrt(sxx * syy);
}

/// What a scripted slide sent to the controller, keyed by the xrsim frame number it logs.
struct Slide {
  std::map<std::uint64_t, std::vector<vt::haptics::ActuatorFrame>> pushed;  // frames given to the sink
  std::map<std::uint64_t, float> mapValue;  // vibration map under the fingertip
  vt::xr::ControllerHaptics mode = vt::xr::ControllerHaptics::Rumble;
  vt::xr::ControllerHaptics leftMode = vt::xr::ControllerHaptics::Rumble;  // the other controller's
  std::int64_t displayPeriod_ns = 0;
  float lowestTip_m = 1.0f;
  std::uint32_t validationMessages = 0;
  std::uint64_t pcmDropped = 0;  // the sink's PCM counters at the end
  std::size_t pcmPending = 0;
};

// The index tip slides 2 mm deep across the stripes plate (centre x = -0.27, top y = 0.006)
// from x = -0.33 to -0.21 in 1.2 s, starting above it and lifting off at the end. The haptic
// loop would run on its own thread at 1 kHz; here it ticks `ticksPerFrame` times per display
// frame, deterministically, and the sink gets every frame and one flush per display frame.
Slide runSlide(const std::filesystem::path& dir, const std::map<std::string, std::string>& extraEnv, int ticksPerFrame) {
  const vt::xr::HeadsetOptions defaults;
  json keyframes = json::array();
  keyframes.push_back(handKeyframe(0.0, handWithIndexTipAt({-0.33f, 0.05f, 0.0f}), defaults.T_stage_world));
  const int steps = 24;
  for (int k = 0; k <= steps; ++k) {
    const float x = -0.33f + 0.12f * float(k) / float(steps);
    keyframes.push_back(handKeyframe(0.2 + 1.2 * k / steps, handWithIndexTipAt({x, 0.012f, 0.0f}), defaults.T_stage_world));
  }
  keyframes.push_back(handKeyframe(1.6, handWithIndexTipAt({-0.21f, 0.05f, 0.0f}), defaults.T_stage_world));
  std::ofstream(dir / "script.json") << json{{"keyframes", keyframes}}.dump();

  auto env = vt::test::xrsimEnv(dir, 170);  // 170 frames at 90 Hz: past the end of the script
  env.insert_or_assign("XRSIM_SCRIPT", (dir / "script.json").string());
  for (const auto& [key, value] : extraEnv) env.insert_or_assign(key, value);
  vt::test::ScopedEnv scoped(env);

  auto history = std::make_unique<vt::PoseHistory>();
  vt::PoseHistory& poses = *history;
  vt::xr::HeadsetOptions options = vt::test::fixedPlacement();
  options.handOutputs[1] = &poses;
  options.validate = true;
  auto opened = vt::xr::Headset::open(options);
  REQUIRE(opened.headset);
  vt::xr::Headset& headset = *opened.headset;
  REQUIRE(headset.handTracking());

  auto scene = std::make_shared<const vt::Scene>(vt::makeDemoScene());
  vt::haptics::HapticConfig config;
  config.contacts = {{vt::HandJoint::IndexTip}};
  config.routes = {{0, vt::haptics::ActuatorId::Index}};
  // Stepped xrsim: the script runs on virtual display time while poses are stamped with the
  // wall clock (no timespec conversion), so these sink tests tick on the newest pose.
  config.sampling.mode = vt::PoseSampling::Latest;
  vt::haptics::HapticLoop loop(config, poses);
  vt::SpscRing<vt::haptics::ActuatorFrame> frames(64);
  loop.addOutput(frames);
  vt::SpscRing<vt::haptics::ContactTrace> traces(64);
  loop.setTraceOutput(traces);
  loop.publishScene(vt::haptics::makeHapticScene(scene));
  vt::xr::XrHapticSink sink(headset, 1);

  Slide slide;
  slide.mode = sink.mode();
  slide.leftMode = headset.controllerHaptics(0);
  std::uint64_t displayFrames = 0;
  vt::renderer::Renderer renderer(headset.device());
  renderer.setScene(scene);
  vt::test::runLoop(headset, renderer, 400, [&] {
    ++displayFrames;
    vt::HandPose pose;
    REQUIRE(poses.newest(pose));
    // xrsim logs the frame count at the time of the call: the next frame's number.
    const std::uint64_t logged = displayFrames + 1;
    // 1 ms apart, ending at the pose's time (the display period is 11.1 ms: ticks stay in order).
    for (int t = 0; t < ticksPerFrame; ++t)
      REQUIRE(loop.tickOnce(pose.t_ns - std::int64_t(ticksPerFrame - 1 - t) * 1'000'000));
    vt::haptics::ActuatorFrame frame;
    while (frames.pop(frame)) {
      sink.push(frame);
      slide.pushed[logged].push_back(frame);
    }
    sink.flush();
    vt::haptics::ContactTrace trace;
    while (traces.pop(trace))
      if (trace.inContact) slide.mapValue[logged] = trace.mapValue;
    if (pose.valid) slide.lowestTip_m = std::min(slide.lowestTip_m, pose.at(vt::HandJoint::IndexTip).y);
  });
  slide.pcmDropped = sink.pcmSamplesDropped();
  slide.pcmPending = sink.pcmSamplesPending();
  renderer.waitIdle();
  slide.displayPeriod_ns = headset.displayPeriod_ns();
  slide.validationMessages = headset.device()->validationMessageCount();
  return slide;
}

std::vector<json> readLog(const std::filesystem::path& path) {
  std::ifstream log(path);
  REQUIRE(log);
  std::vector<json> entries;
  std::string line;
  while (std::getline(log, line)) entries.push_back(json::parse(line));
  return entries;
}

}  // namespace

TEST_CASE("xr hand tracking slide across the stripes plate drives logged controller haptics") {
  const auto dir = vt::test::outputDir("xr_hand_slide");
  const Slide slide = runSlide(dir, {}, 1);
  CHECK(slide.mode == vt::xr::ControllerHaptics::Rumble);  // xrsim offers no FB haptics by default
  CHECK(slide.validationMessages == 0);
  // XR joints arrive in scene coordinates where the script put them (the slide's height).
  CHECK(std::abs(slide.lowestTip_m - 0.012f) < 0.0005f);

  std::map<std::uint64_t, float> sentAmplitude;  // frame number -> amplitude the sink sent
  for (const auto& [frame, pushed] : slide.pushed)
    if (pushed.back().intensity[1] > 0.0f) sentAmplitude[frame] = std::min(1.0f, pushed.back().intensity[1]);
  std::vector<float> amplitudes;
  int stops = 0;
  for (const json& entry : readLog(dir / "haptics.jsonl")) {
    CHECK(entry["hand"] == "right");
    if (entry["event"] == "stop") {
      ++stops;
      continue;
    }
    REQUIRE(entry["event"] == "apply");
    amplitudes.push_back(entry["amplitude"].get<float>());
    CHECK(entry["duration_ns"].get<std::int64_t>() == slide.displayPeriod_ns);
    const auto sent = sentAmplitude.find(entry["frame"].get<std::uint64_t>());
    if (sent != sentAmplitude.end()) CHECK(entry["amplitude"].get<float>() == Approx(sent->second));
  }
  INFO("pulses " << amplitudes.size());
  CHECK(amplitudes.size() >= 40);  // the finger is on the plate for ~1.2 s = ~100 frames
  CHECK(stops >= 1);               // lifting off stops the vibration
  // Stripes: the amplitude rises and falls along the path instead of staying constant...
  const auto [lo, hi] = std::minmax_element(amplitudes.begin(), amplitudes.end());
  CHECK(*hi - *lo > 0.2f);
  // ...and follows the vibration map under the fingertip (Pearson correlation over the pulses).
  std::vector<std::pair<double, double>> pairs;
  for (const auto& [frame, amplitude] : sentAmplitude)
    if (const auto m = slide.mapValue.find(frame); m != slide.mapValue.end()) pairs.emplace_back(m->second, amplitude);
  REQUIRE(pairs.size() >= 40);
  const double correlation = pearson(pairs);
  INFO("map/amplitude correlation " << correlation << " over " << pairs.size() << " pulses");
  CHECK(correlation > 0.8);
}

TEST_CASE("xr PCM haptics: the controller plays the texture waveform, which follows the map along a slide") {
  const auto dir = vt::test::outputDir("xr_pcm_slide");
  // XR_FB_haptic_pcm offered (with the envelope): the sink sends PCM, 11 ticks per 90 Hz frame.
  const Slide slide = runSlide(dir, {{"XRSIM_HAPTIC_PCM", "1"}, {"XRSIM_HAPTIC_ENVELOPE", "1"}}, 11);
  REQUIRE(slide.mode == vt::xr::ControllerHaptics::Pcm);
  CHECK(slide.validationMessages == 0);
  std::vector<std::pair<double, double>> pairs;  // map value, RMS of the PCM buffer
  std::vector<double> rms;
  int buffers = 0, stops = 0;
  for (const json& entry : readLog(dir / "haptics.jsonl")) {
    if (entry["event"] == "stop") {
      ++stops;
      continue;
    }
    REQUIRE(entry["event"] == "pcm");
    ++buffers;
    CHECK(entry["sample_rate_hz"].get<float>() == 8000.0f);
    CHECK(entry["append"].get<bool>());  // back to back: no gap between display frames
    const auto samples = entry["samples"].get<std::vector<float>>();
    // The logged samples are exactly the blocks the loop rendered in that display frame.
    const auto pushed = slide.pushed.find(entry["frame"].get<std::uint64_t>());
    REQUIRE(pushed != slide.pushed.end());
    std::vector<float> expected;
    for (const auto& frame : pushed->second)
      for (int s = 0; s < frame.blockLength; ++s) expected.push_back(frame.block[1][std::size_t(s)]);
    REQUIRE(samples.size() == expected.size());
    CHECK(samples.size() == 11u * 8u);
    for (std::size_t i = 0; i < samples.size(); ++i) REQUIRE(samples[i] == Approx(expected[i]).margin(1e-6));
    double energy = 0.0;
    for (float s : samples) energy += double(s) * double(s);
    rms.push_back(std::sqrt(energy / double(samples.size())));
    if (const auto m = slide.mapValue.find(pushed->first); m != slide.mapValue.end()) pairs.emplace_back(m->second, rms.back());
  }
  INFO("PCM buffers " << buffers);
  CHECK(buffers >= 40);
  CHECK(stops >= 1);  // lifting off stops the queued waveform
  const auto [lo, hi] = std::minmax_element(rms.begin(), rms.end());
  CHECK(*hi > 2.0 * *lo);  // the stripes come and go in the waveform's strength
  REQUIRE(pairs.size() >= 40);
  const double correlation = pearson(pairs);
  WARN("xr PCM: map/RMS correlation " << correlation << " over " << pairs.size() << " buffers");
  CHECK(correlation > 0.8);
}

TEST_CASE("xr PCM haptics: samples the runtime does not take are offered again, a short backlog at most") {
  const auto dir = vt::test::outputDir("xr_pcm_capacity");
  // 88 samples per display frame against a motor buffer that takes 64 per call.
  const Slide slide = runSlide(dir, {{"XRSIM_HAPTIC_PCM", "1"}, {"XRSIM_HAPTIC_PCM_CAPACITY", "64"}}, 11);
  REQUIRE(slide.mode == vt::xr::ControllerHaptics::Pcm);
  std::vector<float> rendered;  // every sample the sink was given, in order
  for (const auto& [frame, frames] : slide.pushed)
    for (const auto& f : frames)
      for (int s = 0; s < f.blockLength; ++s) rendered.push_back(f.block[1][std::size_t(s)]);
  std::vector<std::vector<float>> taken;
  std::size_t takenCount = 0;
  for (const json& entry : readLog(dir / "haptics.jsonl")) {
    if (entry["event"] != "pcm") continue;
    taken.push_back(entry["samples"].get<std::vector<float>>());
    CHECK(taken.back().size() <= 64u);
    takenCount += taken.back().size();
  }
  REQUIRE(taken.size() >= 40);
  INFO("rendered " << rendered.size() << ", taken " << takenCount << ", dropped " << slide.pcmDropped
                   << ", pending " << slide.pcmPending);
  // 24 samples a frame more than the runtime takes: the backlog stays bounded by dropping the oldest.
  CHECK(slide.pcmDropped > 0);
  CHECK(slide.pcmPending <= std::size_t(vt::xr::XrHapticSink::kMaxPcmBacklog_s * 8000.0));
  CHECK(takenCount + slide.pcmDropped + slide.pcmPending <= rendered.size());
  // Each buffer taken is a contiguous run of the rendered waveform, later than the one before:
  // what the runtime left is played next instead of being skipped.
  std::size_t at = 0;
  for (const auto& buffer : taken) {
    const auto found = std::search(rendered.begin() + long(at), rendered.end(), buffer.begin(), buffer.end(),
                                   [](float a, float b) { return std::abs(a - b) <= 1e-6f; });
    REQUIRE(found != rendered.end());
    at = std::size_t(found - rendered.begin()) + buffer.size();
  }
}

TEST_CASE("xr amplitude-envelope haptics: one amplitude per haptic tick over the ticks' duration") {
  const auto dir = vt::test::outputDir("xr_envelope_slide");
  const Slide slide = runSlide(dir, {{"XRSIM_HAPTIC_ENVELOPE", "1"}}, 11);
  REQUIRE(slide.mode == vt::xr::ControllerHaptics::AmplitudeEnvelope);
  int envelopes = 0;
  for (const json& entry : readLog(dir / "haptics.jsonl")) {
    if (entry["event"] == "stop") continue;
    REQUIRE(entry["event"] == "envelope");
    ++envelopes;
    const auto amplitudes = entry["amplitudes"].get<std::vector<float>>();
    const auto pushed = slide.pushed.find(entry["frame"].get<std::uint64_t>());
    REQUIRE(pushed != slide.pushed.end());
    REQUIRE(amplitudes.size() == pushed->second.size());
    for (std::size_t i = 0; i < amplitudes.size(); ++i)
      CHECK(amplitudes[i] == Approx(std::min(1.0f, pushed->second[i].intensity[1])));
    CHECK(entry["duration_ns"].get<std::int64_t>() == std::int64_t(amplitudes.size()) * 1'000'000);
  }
  CHECK(envelopes >= 40);
}

TEST_CASE("xr parametric haptics: the logged curves follow the map along a slide, streamed frame by frame") {
  const auto dir = vt::test::outputDir("xr_parametric_slide");
  // PCM on the left controller only: the right one (the sink's) falls back to parametric.
  const Slide slide = runSlide(dir, {{"XRSIM_HAPTIC_PARAMETRIC", "1"}, {"XRSIM_HAPTIC_PCM", "1"},
                                     {"XRSIM_HAPTIC_PCM_HANDS", "left"}, {"XRSIM_HAPTIC_ENVELOPE", "1"}}, 11);
  REQUIRE(slide.mode == vt::xr::ControllerHaptics::Parametric);
  CHECK(slide.leftMode == vt::xr::ControllerHaptics::Pcm);
  std::vector<std::pair<double, double>> pairs;  // map under the fingertip, mean logged amplitude
  std::int64_t last_ns = -1;
  int frames = 0, starts = 0;
  for (const json& entry : readLog(dir / "haptics.jsonl")) {
    CHECK(entry["hand"] == "right");
    if (entry["event"] == "stop") {
      last_ns = -1;
      continue;
    }
    REQUIRE(entry["event"] == "parametric");
    ++frames;
    const auto amplitude = entry["amplitude"].get<std::vector<std::pair<std::int64_t, float>>>();
    const auto frequency = entry["frequency"].get<std::vector<std::pair<std::int64_t, float>>>();
    REQUIRE(amplitude.size() <= 500u);
    REQUIRE(frequency.size() == amplitude.size());
    if (entry["stream"] == "first") {
      ++starts;
      CHECK(amplitude.front().first == 0);
      CHECK(entry["min_frequency_hz"].get<float>() == vt::haptics::kMinFrequency_hz);
      CHECK(entry["max_frequency_hz"].get<float>() == vt::haptics::kMaxFrequency_hz);
    } else {
      REQUIRE(entry["stream"] == "intermediate");
      CHECK(amplitude.front().first >= last_ns);  // the stream's time runs on
      CHECK(entry["min_frequency_hz"].get<float>() == 0.0f);
    }
    last_ns = amplitude.back().first;
    // One point per haptic tick, 1 ms apart, carrying the tick's level.
    const auto pushed = slide.pushed.find(entry["frame"].get<std::uint64_t>());
    REQUIRE(pushed != slide.pushed.end());
    REQUIRE(amplitude.size() == pushed->second.size());
    double sum = 0.0;
    for (std::size_t i = 0; i < amplitude.size(); ++i) {
      CHECK(amplitude[i].second == Approx(std::min(1.0f, pushed->second[i].intensity[1])));
      if (i > 0) CHECK(amplitude[i].first - amplitude[i - 1].first == 1'000'000);
      CHECK(frequency[i].second == Approx(vt::haptics::normaliseFrequency(pushed->second[i].frequency_hz[1])));
      sum += amplitude[i].second;
    }
    if (const auto m = slide.mapValue.find(entry["frame"].get<std::uint64_t>()); m != slide.mapValue.end())
      pairs.emplace_back(m->second, sum / double(amplitude.size()));
  }
  CHECK(frames >= 40);
  CHECK(starts >= 1);
  REQUIRE(pairs.size() >= 40);
  const double correlation = pearson(pairs);
  INFO("map/parametric amplitude correlation " << correlation << " over " << pairs.size() << " frames");
  CHECK(correlation > 0.8);
}

TEST_CASE("xr controllers without hand tracking pose a hand whose index curls with the trigger") {
  const auto dir = vt::test::outputDir("xr_controllers");
  json script = {{"keyframes",
                  {{{"t", 0.0}, {"right", {{"buttons", {{"trigger", 0.0}, {"select", 0.0}}}}}},
                   {{"t", 0.3}, {"right", {{"buttons", {{"trigger", 0.0}, {"select", 0.0}}}}}},
                   {{"t", 0.4}, {"right", {{"buttons", {{"trigger", 1.0}, {"select", 1.0}}}}}}}}};
  std::ofstream(dir / "script.json") << script.dump();
  for (const char* profile : {"/interaction_profiles/valve/index_controller", "/interaction_profiles/htc/vive_controller",
                              "/interaction_profiles/oculus/touch_controller", "/interaction_profiles/khr/simple_controller"}) {
    INFO(profile);
    auto env = vt::test::xrsimEnv(dir, 60);
    env.insert_or_assign("XRSIM_SCRIPT", (dir / "script.json").string());
    env.insert_or_assign("XRSIM_HAND_TRACKING", std::string("0"));
    env.insert_or_assign("XRSIM_PROFILE", std::string(profile));
    vt::test::ScopedEnv scoped(env);
    auto history = std::make_unique<vt::PoseHistory>();
    vt::PoseHistory& poses = *history;
    vt::xr::HeadsetOptions options = vt::test::fixedPlacement();
    options.handOutputs[1] = &poses;
    auto opened = vt::xr::Headset::open(options);
    REQUIRE(opened.headset);
    CHECK_FALSE(opened.headset->handTracking());
    vt::renderer::Renderer renderer(opened.headset->device());
    renderer.setScene(std::make_shared<const vt::Scene>(vt::makeDemoScene()));
    std::vector<float> tipToPalm;
    glm::vec3 palm{0.0f};
    vt::test::runLoop(*opened.headset, renderer, 200, [&] {
      vt::HandPose pose;
      REQUIRE(poses.newest(pose));
      REQUIRE(pose.valid);
      palm = pose.at(vt::HandJoint::Palm);
      tipToPalm.push_back(glm::distance(pose.at(vt::HandJoint::IndexTip), palm));
    });
    renderer.waitIdle();
    CHECK(opened.headset->inputSource() == profile);
    REQUIRE(tipToPalm.size() > 40);
    INFO("index tip to palm: first " << tipToPalm.front() << " m, last " << tipToPalm.back() << " m");
    CHECK(tipToPalm.back() < tipToPalm.front() - 0.02f);  // the index finger curled in
    // xrsim's right grip is at stage (0.2, 1.3, -0.35): in scene coordinates minus T_stage_world.
    const glm::vec3 grip_world = glm::vec3(glm::inverse(options.T_stage_world) * glm::vec4(0.2f, 1.3f, -0.35f, 1.0f));
    CHECK(glm::distance(palm, grip_world) < 0.05f);
  }
}

TEST_CASE("xr haptic-side sampler skips periods it already posed when the lookahead shrinks") {
  // The sampler asks the runtime for the hand at now + lookahead every millisecond. When the
  // lookahead drops by 100 ms, those times lie before poses already published: it must wait for
  // time to pass them, not publish a pose a nanosecond after the last (its velocity, over that
  // span, is the runtime's rounding, magnified by prediction).
  const auto dir = vt::test::outputDir("xr_sampler_lookahead");
  std::ofstream(dir / "script.json") << R"({"keyframes": [{"t": 0, "right": {"buttons": {"trigger": 0.0, "squeeze": 0.0}}}, {"t": 1}]})";
  auto env = vt::test::xrsimEnv(dir, 60);
  env.insert_or_assign("XRSIM_SCRIPT", (dir / "script.json").string());
  env.insert_or_assign("XRSIM_REALTIME", std::string("1"));  // wall-clock XrTime: the sampler runs
  vt::test::ScopedEnv scoped(env);
  auto history = std::make_unique<vt::PoseHistory>();
  vt::xr::HeadsetOptions options = vt::test::fixedPlacement();
  options.handOutputs[1] = history.get();
  auto headset = vt::test::openValidatedHeadset(options);
  headset->setHandLookahead(100'000'000);
  vt::renderer::Renderer renderer(headset->device());
  renderer.setScene(std::make_shared<const vt::Scene>(vt::makeDemoScene()));
  int frames = 0;
  std::uint64_t publishedAtDrop = 0;
  vt::test::runLoop(*headset, renderer, 400, [&] {
    if (++frames == 30) {  // a third of a second in, at 90 Hz
      publishedAtDrop = history->published();
      headset->setHandLookahead(0);
    }
  });
  renderer.waitIdle();
  REQUIRE(publishedAtDrop > 10);  // the sampler ran before the drop
  REQUIRE(history->published() > publishedAtDrop + 10);  // and after it
  std::int64_t closest_ns = std::numeric_limits<std::int64_t>::max();
  vt::HandPose before, pose;
  std::uint32_t segment = 0;
  REQUIRE(history->at(0, before, segment));
  for (std::uint64_t i = 1; i < history->published(); ++i) {
    REQUIRE(history->at(i, pose, segment));
    closest_ns = std::min(closest_ns, pose.t_ns - before.t_ns);
    before = pose;
  }
  INFO("closest stamps " << closest_ns << " ns apart over " << history->published() << " poses");
  CHECK(closest_ns >= 500'000);
  CHECK(headset->device()->validationMessageCount() == 0);
}
