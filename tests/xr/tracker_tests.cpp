// The glove's VIVE tracker (XR_HTCX_vive_tracker_interaction) through xrsim: it gives the right
// hand's gross pose when hand tracking has no joints, the glove's flexion curls the fingers;
// without the extension, or without a tracker, controllers pose the hand as before.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "test_support.hpp"
#include "vt/scene/demo_scene.hpp"
#include "xr_fixture.hpp"

using nlohmann::json;

namespace {

// The tracker's keyframes in the stage frame: it moves and turns a quarter turn about +Y.
const glm::vec3 kStart_stage{0.1f, 1.0f, -0.4f}, kEnd_stage{-0.1f, 1.1f, -0.5f};
const glm::quat kEndTurn = glm::angleAxis(glm::half_pi<float>(), glm::vec3(0.0f, 1.0f, 0.0f));
// The documented mounting: the palm centre is 3 cm along the tracker's -Y.
const glm::vec3 kPalm_tracker{0.0f, -0.03f, 0.0f};

json trackerScript(bool withTracker) {
  json start = {{"t", 0.0}, {"right", {{"buttons", {{"trigger", 0.0}, {"squeeze", 0.0}}}}}};
  json end = {{"t", 0.3}};
  if (withTracker) {
    start["tracker"] = {{"position", {kStart_stage.x, kStart_stage.y, kStart_stage.z}}, {"orientation", {0, 0, 0, 1}}};
    end["tracker"] = {{"position", {kEnd_stage.x, kEnd_stage.y, kEnd_stage.z}},
                      {"orientation", {kEndTurn.x, kEndTurn.y, kEndTurn.z, kEndTurn.w}}};
  }
  return {{"keyframes", {start, end}}};
}

struct Run {
  std::vector<vt::HandPose> poses;  // the right hand, one per rendered frame
  std::string inputSource;
  bool viveTracker = false;
  std::uint64_t validationMessages = 0;
};

Run run(const std::string& name, bool withTracker, vt::xr::HeadsetOptions options,
        vt::LatestValue<vt::FingerCurls>* glove = nullptr) {
  const auto dir = vt::test::outputDir(name);
  std::ofstream(dir / "script.json") << trackerScript(withTracker).dump();
  auto env = vt::test::xrsimEnv(dir, 60);
  env.insert_or_assign("XRSIM_SCRIPT", (dir / "script.json").string());
  vt::test::ScopedEnv scoped(env);  // hand tracking supported, but the script has no joints
  auto history = std::make_unique<vt::PoseHistory>();
  vt::PoseHistory& poses = *history;
  options.handOutputs[1] = &poses;
  auto headset = vt::test::openValidatedHeadset(options);
  vt::renderer::Renderer renderer(headset->device());
  renderer.setScene(std::make_shared<const vt::Scene>(vt::makeDemoScene()));
  Run out;
  vt::test::runLoop(*headset, renderer, 200, [&] {
    vt::HandPose pose;
    REQUIRE(poses.newest(pose));
    REQUIRE(pose.valid);
    out.poses.push_back(pose);
    // Halfway through, the glove reports a straighter index finger.
    if (glove != nullptr && out.poses.size() == 30) glove->publish({0.1f, 0.0f, 0.8f, 0.8f, 0.8f});
  });
  renderer.waitIdle();
  out.inputSource = headset->inputSource();
  out.viveTracker = headset->viveTracker();
  out.validationMessages = headset->device()->validationMessageCount();
  return out;
}

float maxJointDistance(const vt::HandPose& a, const vt::HandPose& b) {
  float worst = 0.0f;
  for (int j = 0; j < vt::kHandJointCount; ++j)
    worst = std::max(worst, glm::distance(a.position[std::size_t(j)], b.position[std::size_t(j)]));
  return worst;
}

}  // namespace

TEST_CASE("xr vive tracker poses the right palm and the glove curls its fingers") {
  vt::LatestValue<vt::FingerCurls> glove;
  glove.publish({0.6f, 0.9f, 0.9f, 0.9f, 0.9f});
  vt::xr::HeadsetOptions options = vt::test::fixedPlacement();
  options.gloveCurls = &glove;
  const Run r = run("xr_vive_tracker", true, options, &glove);
  CHECK(r.viveTracker);
  CHECK(r.inputSource == "vive tracker (handheld_object)");
  CHECK(r.validationMessages == 0);
  REQUIRE(r.poses.size() > 40);

  const glm::mat4 T_world_stage = glm::inverse(options.T_stage_world);
  auto palmWorld = [&](const glm::vec3& p_stage) {  // the turn is about Y: the palm offset stays -Y
    return glm::vec3(T_world_stage * glm::vec4(p_stage + kPalm_tracker, 1.0f));
  };
  // Every palm lies on the tracker's path (shifted to the palm), moving from start to end.
  const glm::vec3 a = palmWorld(kStart_stage), b = palmWorld(kEnd_stage);
  float worstOffPath = 0.0f;
  for (const vt::HandPose& pose : r.poses) {
    const glm::vec3 p = pose.at(vt::HandJoint::Palm);
    const float s = std::clamp(glm::dot(p - a, b - a) / glm::dot(b - a, b - a), 0.0f, 1.0f);
    worstOffPath = std::max(worstOffPath, glm::distance(p, a + s * (b - a)));
  }
  INFO("palm farthest from the tracker's path: " << worstOffPath << " m");
  CHECK(worstOffPath < 0.002f);
  CHECK(glm::distance(r.poses.front().at(vt::HandJoint::Palm), a) < 0.02f);

  // At the end (the script holds its last keyframe) the whole hand is poseHand() at the tracker's
  // palm frame with the glove's latest curls.
  const glm::mat4 T_stage_palm = glm::translate(glm::mat4(1.0f), kEnd_stage) * glm::mat4_cast(kEndTurn) *
                                 glm::translate(glm::mat4(1.0f), kPalm_tracker);
  const vt::HandPose expectedEnd =
      vt::poseHand(T_world_stage * T_stage_palm, vt::FingerCurls{0.1f, 0.0f, 0.8f, 0.8f, 0.8f});
  const float endError = maxJointDistance(r.poses.back(), expectedEnd);
  INFO("last pose vs the tracker with the glove's curls: " << endError << " m");
  CHECK(endError < 0.001f);
  // Before the glove's second report the index finger was curled in: its tip nearer the palm.
  const auto tipToPalm = [](const vt::HandPose& p) {
    return glm::distance(p.at(vt::HandJoint::IndexTip), p.at(vt::HandJoint::Palm));
  };
  CHECK(tipToPalm(r.poses[10]) < tipToPalm(r.poses.back()) - 0.02f);
}

TEST_CASE("xr without the vive tracker extension or a tracker the controllers pose the hand") {
  // xrsim's right grip is at stage (0.2, 1.3, -0.35), the tracker starts elsewhere.
  for (const bool requestExtension : {false, true}) {
    const bool scriptTracker = !requestExtension;  // extension off with a tracker, on without one
    INFO("extension requested " << requestExtension << ", tracker scripted " << scriptTracker);
    vt::LatestValue<vt::FingerCurls> glove;
    glove.publish({0.1f, 0.0f, 0.0f, 0.0f, 0.0f});
    vt::xr::HeadsetOptions options = vt::test::fixedPlacement();
    options.useTracker = requestExtension;
    options.preferHandTracking = false;  // so inputSource() names the controllers' profile
    options.gloveCurls = &glove;
    const Run r = run(requestExtension ? "xr_tracker_absent" : "xr_tracker_off", scriptTracker, options);
    CHECK(r.viveTracker == requestExtension);
    CHECK(r.inputSource == "/interaction_profiles/valve/index_controller");
    CHECK(r.validationMessages == 0);
    REQUIRE(r.poses.size() > 40);
    const glm::vec3 grip_world = glm::vec3(glm::inverse(options.T_stage_world) * glm::vec4(0.2f, 1.3f, -0.35f, 1.0f));
    CHECK(glm::distance(r.poses.back().at(vt::HandJoint::Palm), grip_world) < 0.05f);
  }
}
