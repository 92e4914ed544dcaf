#include "motion.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "vt/core/error.hpp"
#include "vt/scene/camera.hpp"
#include "vt/scene/hand.hpp"
#include "vt/xr/headset.hpp"

namespace vt::live {
namespace {

constexpr double kKeyStep_s = 0.004;       // xrsim keyframes along a move
constexpr float kPressDepth_m = 0.003f;    // a pressing fingertip sinks this far into the plate
constexpr float kHover_m = 0.02f;          // a lifted fingertip hovers this high
constexpr float kTipRadius_m = 0.008f;
constexpr double kPressRamp_s = 0.04;      // a fingertip goes down or up in this long (no teleport)
constexpr double kBetweenRounds_s = 0.5;

double minimumJerk(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau);
}

// The fingertip at time t of the motion: minimum-jerk between the keyframes around t.
MotionKey at(const std::vector<MotionKey>& keys, double t_s) {
  if (t_s <= keys.front().t_s) return keys.front();
  for (std::size_t i = 1; i < keys.size(); ++i) {
    if (t_s > keys[i].t_s) continue;
    const MotionKey& a = keys[i - 1];
    const MotionKey& b = keys[i];
    const auto s = float(minimumJerk((t_s - a.t_s) / (b.t_s - a.t_s)));
    return {t_s, a.x_m + (b.x_m - a.x_m) * s, a.z_m + (b.z_m - a.z_m) * s, a.press};
  }
  return keys.back();
}

// 0 hovering .. 1 pressing: ramps after each keyframe that changes the press.
float pressLevel(const std::vector<MotionKey>& keys, double t_s) {
  float level = keys.front().press ? 1.0f : 0.0f;
  for (std::size_t i = 1; i < keys.size() && keys[i].t_s <= t_s; ++i) {
    if (keys[i].press == keys[i - 1].press) continue;
    const auto ramp = float(std::clamp((t_s - keys[i].t_s) / kPressRamp_s, 0.0, 1.0));
    level = keys[i].press ? ramp : 1.0f - ramp;
  }
  return level;
}

}  // namespace

std::vector<MotionKey> personMotions(int rounds) {
  // Peak speed of a minimum-jerk move: 1.875 x distance / duration.
  static const std::vector<MotionKey> round = {
      {0.0, -0.06f, 0.0f, false},  {0.6, -0.06f, 0.0f, true},    // touch down
      {1.0, -0.06f, 0.0f, true},   {1.8, 0.02f, 0.0f, true},     // reach 8 cm in 0.8 s (0.19 m/s), stop
      {2.2, 0.02f, 0.0f, true},    {2.5, -0.04f, 0.0f, true},    // back 6 cm in 0.3 s (0.38 m/s) ...
      {2.8, 0.0f, 0.0f, true},                                   // ... reversing without a stop
      {5.3, 0.03f, 0.0f, true},                                  // slow: 3 cm in 2.5 s (0.022 m/s)
      {5.6, 0.03f, 0.0f, false},   {5.9, -0.05f, 0.0f, false},   // lift off, back in the air
      {6.2, -0.05f, 0.0f, true},   {6.575, 0.05f, 0.0f, true},   // re-touch, 10 cm in 0.375 s (0.5 m/s)
      {7.2, 0.05f, 0.0f, true},    {7.5, 0.05f, 0.0f, false}};   // rest, lift off
  // Rounds 0.5 s in the air apart (back to the start).
  std::vector<MotionKey> all;
  for (int r = 0; r < rounds; ++r)
    for (MotionKey k : round) {
      k.t_s += r * (round.back().t_s + kBetweenRounds_s);
      all.push_back(k);
    }
  return all;
}

void writeCursorScript(const std::filesystem::path& file, const std::vector<MotionKey>& keys, const std::string& size) {
  int width = 0, height = 0;
  if (std::sscanf(size.c_str(), "%dx%d", &width, &height) != 2 || width <= 0 || height <= 0)
    fail("live: window size '", size, "' is not WxH");
  // The grating scene's camera (the default orbit camera) for the window's aspect.
  const CameraView view = OrbitCamera{}.view(float(width) / float(height));
  const glm::mat4 T_eye_world = glm::inverse(view.T_world_eye);
  std::ofstream out(file);
  out << "# t_s x y press (x, y: fractions of the window)\n";
  for (const MotionKey& k : keys) {
    const glm::vec3 eye = glm::vec3(T_eye_world * glm::vec4(k.x_m, 0.0f, k.z_m, 1.0f));
    const float x = (eye.x / -eye.z - view.tanLeft) / (view.tanRight - view.tanLeft);
    const float y = (view.tanUp - eye.y / -eye.z) / (view.tanUp - view.tanDown);
    if (!(x >= 0.0f && x <= 1.0f && y >= 0.0f && y <= 1.0f)) fail("live: motion point ", k.x_m, " m is outside the view");
    char line[96];
    std::snprintf(line, sizeof line, "%.4f %.6f %.6f %d\n", k.t_s, double(x), double(y), int(k.press));
    out << line;
  }
  if (!out) fail(file.string(), ": cannot write the cursor script");
}

void writeXrsimScript(const std::filesystem::path& file, const std::vector<MotionKey>& keys, double rest_s) {
  // The table where --fixed-table keeps it; the plate's top is the scene's y = 0.
  const glm::mat4 T_stage_world = xr::HeadsetOptions{}.T_stage_world;
  auto joints = [&](const MotionKey& k, float press) {
    nlohmann::json list = nlohmann::json::array();
    const float tipY = kTipRadius_m + kHover_m - press * (kHover_m + kPressDepth_m);
    for (int j = 0; j < kHandJointCount; ++j) {
      // Only the index fingertip comes near the plate; the rest of the hand stays well above it.
      const glm::vec3 world = j == int(HandJoint::IndexTip) ? glm::vec3(k.x_m, tipY, k.z_m) : glm::vec3(0.0f, 0.5f, 0.0f);
      const glm::vec3 p = glm::vec3(T_stage_world * glm::vec4(world, 1.0f));
      list.push_back({{"position", {p.x, p.y, p.z}}, {"orientation", {0.0, 0.0, 0.0, 1.0}}, {"radius", kTipRadius_m}});
    }
    return list;
  };
  nlohmann::json frames = nlohmann::json::array();
  frames.push_back({{"t", 0.0}, {"right", {{"tracked", true}, {"joints", joints(keys.front(), pressLevel(keys, 0.0))}}}});
  for (double t = 0.0; t <= keys.back().t_s + 1e-9; t += kKeyStep_s) {
    frames.push_back({{"t", rest_s + t}, {"right", {{"tracked", true}, {"joints", joints(at(keys, t), pressLevel(keys, t))}}}});
  }
  std::ofstream out(file);
  out << nlohmann::json{{"keyframes", frames}}.dump();
  if (!out) fail(file.string(), ": cannot write the xrsim script");
}

}  // namespace vt::live
