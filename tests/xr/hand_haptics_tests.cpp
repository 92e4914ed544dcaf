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

}  // namespace

TEST_CASE("xr hand tracking slide across the stripes plate drives logged controller haptics") {
  const auto dir = vt::test::outputDir("xr_hand_slide");
  const vt::xr::HeadsetOptions defaults;
  // The index tip slides 2 mm deep across the stripes plate (centre x = -0.27, top y = 0.006)
  // from x = -0.33 to -0.21 in 1.2 s, starting above it and lifting off at the end.
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
  vt::test::ScopedEnv scoped(env);

  auto history = std::make_unique<vt::PoseHistory>();
  vt::PoseHistory& poses = *history;
  vt::xr::HeadsetOptions options;
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
  vt::haptics::HapticLoop loop(config, poses);
  vt::LatestValue<vt::haptics::ActuatorFrame> mailbox;
  loop.addOutput(mailbox);
  vt::SpscRing<vt::haptics::ContactTrace> traces(64);
  loop.setTraceOutput(traces);
  loop.publishScene(vt::haptics::makeHapticScene(scene));
  vt::xr::XrHapticSink sink(headset, 1);

  std::map<std::uint64_t, float> sentAmplitude;  // frame number -> amplitude the sink sent
  std::map<std::uint64_t, float> mapValue;       // frame number -> vibration map under the fingertip
  float lowestTip_m = 1.0f;
  std::uint64_t frames = 0;
  vt::renderer::Renderer renderer(headset.device());
  renderer.setScene(scene);
  vt::test::runLoop(headset, renderer, 400, [&] {
    ++frames;
    vt::HandPose pose;
    REQUIRE(poses.newest(pose));
    // The haptic loop would run on its own thread at 1 kHz; one deterministic tick per frame here.
    REQUIRE(loop.tickOnce(pose.t_ns));
    vt::haptics::ActuatorFrame frame;
    REQUIRE(mailbox.read(frame));
    sink.apply(frame);
    // xrsim logs the frame count at the time of the call: the next frame's number.
    if (frame.intensity[1] > 0.0f) sentAmplitude[frames + 1] = std::min(1.0f, frame.intensity[1]);
    vt::haptics::ContactTrace trace;
    while (traces.pop(trace))
      if (trace.inContact) mapValue[frames + 1] = trace.mapValue;
    if (pose.valid) lowestTip_m = std::min(lowestTip_m, pose.at(vt::HandJoint::IndexTip).y);
  });
  renderer.waitIdle();
  CHECK(headset.device()->validationMessageCount() == 0);
  // XR joints arrive in scene coordinates where the script put them (the slide's height).
  CHECK(std::abs(lowestTip_m - 0.012f) < 0.0005f);

  std::ifstream log(dir / "haptics.jsonl");
  REQUIRE(log);
  std::vector<float> amplitudes;
  std::string line;
  int stops = 0;
  while (std::getline(log, line)) {
    const json entry = json::parse(line);
    CHECK(entry["hand"] == "right");
    if (entry["event"] == "stop") {
      ++stops;
      continue;
    }
    amplitudes.push_back(entry["amplitude"].get<float>());
    CHECK(entry["duration_ns"].get<std::int64_t>() == headset.displayPeriod_ns());
    const auto sent = sentAmplitude.find(entry["frame"].get<std::uint64_t>());
    if (sent != sentAmplitude.end()) CHECK(entry["amplitude"].get<float>() == Approx(sent->second));
  }
  INFO("pulses " << amplitudes.size() << " of " << frames << " frames");
  CHECK(amplitudes.size() >= 40);  // the finger is on the plate for ~1.2 s = ~100 frames
  CHECK(stops >= 1);               // lifting off stops the vibration
  // Stripes: the amplitude rises and falls along the path instead of staying constant...
  const auto [lo, hi] = std::minmax_element(amplitudes.begin(), amplitudes.end());
  CHECK(*hi - *lo > 0.2f);
  // ...and follows the vibration map under the fingertip (Pearson correlation over the pulses).
  std::vector<std::pair<double, double>> pairs;
  for (const auto& [frame, amplitude] : sentAmplitude)
    if (const auto m = mapValue.find(frame); m != mapValue.end()) pairs.emplace_back(m->second, amplitude);
  REQUIRE(pairs.size() >= 40);
  double mx = 0, my = 0;
  for (const auto& [x, y] : pairs) mx += x, my += y;
  mx /= double(pairs.size());
  my /= double(pairs.size());
  double sxy = 0, sxx = 0, syy = 0;
  for (const auto& [x, y] : pairs) sxy += (x - mx) * (y - my), sxx += (x - mx) * (x - mx), syy += (y - my) * (y - my);
  const double correlation = sxy / std::sqrt(sxx * syy);
  INFO("map/amplitude correlation " << correlation << " over " << pairs.size() << " pulses");
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
    vt::xr::HeadsetOptions options;
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
