#include "script.hpp"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "vt/core/error.hpp"

namespace xrsim {
namespace {

using nlohmann::json;

Sample defaultSample() {
  Sample s;
  s.head.position = {0.0f, 1.6f, 0.0f};
  s.tracker.position = {0.2f, 1.3f, -0.35f};
  for (int h = 0; h < 2; ++h) {
    const float side = h == 0 ? -1.0f : 1.0f;
    s.hands[h].grip.position = {0.2f * side, 1.3f, -0.35f};
    s.hands[h].aim = s.hands[h].grip;
  }
  return s;
}

glm::vec3 readVec3(const json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3) vt::fail(where, ": expected [x, y, z]");
  for (const auto& v : j)
    if (!v.is_number()) vt::fail(where, ": expected numbers");
  return {j[0].get<float>(), j[1].get<float>(), j[2].get<float>()};
}

glm::quat readQuat(const json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 4) vt::fail(where, ": expected [x, y, z, w]");
  for (const auto& v : j)
    if (!v.is_number()) vt::fail(where, ": expected numbers");
  const glm::quat q(j[3].get<float>(), j[0].get<float>(), j[1].get<float>(), j[2].get<float>());
  const float len = glm::length(q);
  if (!(len > 0.5f && len < 1.5f)) vt::fail(where, ": quaternion is not unit length (", len, ")");
  return glm::normalize(q);
}

void readPose(const json& j, Pose& pose, const std::string& where) {
  if (!j.is_object()) vt::fail(where, ": expected an object with position/orientation");
  if (j.contains("position")) pose.position = readVec3(j["position"], where + ".position");
  if (j.contains("orientation")) pose.orientation = readQuat(j["orientation"], where + ".orientation");
}

void readHand(const json& j, HandSample& hand, const std::string& where) {
  if (!j.is_object()) vt::fail(where, ": expected an object");
  if (j.contains("tracked")) hand.controllerTracked = j["tracked"].get<bool>();
  if (j.contains("grip")) {
    readPose(j["grip"], hand.grip, where + ".grip");
    if (!j.contains("aim")) hand.aim = hand.grip;
  }
  if (j.contains("aim")) readPose(j["aim"], hand.aim, where + ".aim");
  if (j.contains("buttons")) {
    if (!j["buttons"].is_object()) vt::fail(where, ".buttons: expected an object");
    for (const auto& [name, value] : j["buttons"].items()) {
      if (value.is_boolean()) hand.buttons[name] = value.get<bool>() ? 1.0f : 0.0f;
      else if (value.is_number()) hand.buttons[name] = std::clamp(value.get<float>(), 0.0f, 1.0f);
      else if (value.is_array() && value.size() == 2) hand.axes[name] = {value[0].get<float>(), value[1].get<float>()};
      else vt::fail(where, ".buttons.", name, ": expected a number, a boolean or [x, y]");
    }
  }
  if (j.contains("joints")) {
    const json& joints = j["joints"];
    if (joints.is_null()) {
      hand.jointsActive = false;
    } else {
      if (!joints.is_array() || joints.size() != kJointCount)
        vt::fail(where, ".joints: expected null or ", kJointCount, " joints in XR_EXT_hand_tracking order");
      for (int i = 0; i < kJointCount; ++i) {
        const std::string jointWhere = vt::str(where, ".joints[", i, "]");
        readPose(joints[i], hand.joints[i], jointWhere);
        hand.radius_m[i] = joints[i].value("radius", 0.01f);
      }
      hand.jointsActive = true;
    }
  }
}

void readTracker(const json& j, Sample& sample, std::string& role, const std::string& where) {
  readPose(j, sample.tracker, where);
  if (j.contains("tracked")) sample.trackerTracked = j["tracked"].get<bool>();
  if (j.contains("role")) {
    if (!j["role"].is_string() || j["role"].get<std::string>().empty() ||
        j["role"].get<std::string>().find_first_not_of("abcdefghijklmnopqrstuvwxyz_") != std::string::npos)
      vt::fail(where, ".role: expected a role name such as \"handheld_object\"");
    role = j["role"].get<std::string>();
  } else if (role.empty()) {
    role = "handheld_object";
  }
}

Pose lerp(const Pose& a, const Pose& b, float w) {
  return {glm::mix(a.position, b.position, w), glm::slerp(a.orientation, b.orientation, w)};
}

HandSample lerp(const HandSample& a, const HandSample& b, float w) {
  HandSample out = w < 0.5f ? a : b;  // discrete fields switch halfway
  out.grip = lerp(a.grip, b.grip, w);
  out.aim = lerp(a.aim, b.aim, w);
  for (auto& [name, value] : out.buttons) {
    const auto ia = a.buttons.find(name), ib = b.buttons.find(name);
    const float va = ia == a.buttons.end() ? 0.0f : ia->second, vb = ib == b.buttons.end() ? 0.0f : ib->second;
    value = va + (vb - va) * w;
  }
  if (a.jointsActive && b.jointsActive)
    for (int i = 0; i < kJointCount; ++i) {
      out.joints[i] = lerp(a.joints[i], b.joints[i], w);
      out.radius_m[i] = a.radius_m[i] + (b.radius_m[i] - a.radius_m[i]) * w;
    }
  return out;
}

}  // namespace

Script::Script() : m_times{0.0}, m_keys{defaultSample()} {}

Script Script::load(const std::filesystem::path& path) {
  const std::string source = "xrsim script '" + path.string() + "'";
  std::ifstream in(path);
  if (!in) vt::fail(source, ": cannot open");
  json root;
  try {
    root = json::parse(in);
  } catch (const json::exception& e) {
    vt::fail(source, ": invalid JSON: ", e.what());
  }
  if (!root.is_object() || !root.contains("keyframes") || !root["keyframes"].is_array() || root["keyframes"].empty())
    vt::fail(source, ": expected an object with a non-empty 'keyframes' array");
  Script script;
  script.m_times.clear();
  script.m_keys.clear();
  Sample current = defaultSample();  // each keyframe inherits what it does not set
  for (std::size_t k = 0; k < root["keyframes"].size(); ++k) {
    const json& key = root["keyframes"][k];
    const std::string where = vt::str(source, " keyframes[", k, "]");
    try {
      if (!key.is_object() || !key.contains("t") || !key["t"].is_number()) vt::fail(where, ": needs a number 't' (seconds)");
      const double t = key["t"].get<double>();
      if (!script.m_times.empty() && t <= script.m_times.back()) vt::fail(where, ".t: times must increase");
      if (key.contains("head")) readPose(key["head"], current.head, where + ".head");
      if (key.contains("left")) readHand(key["left"], current.hands[0], where + ".left");
      if (key.contains("right")) readHand(key["right"], current.hands[1], where + ".right");
      if (key.contains("tracker")) readTracker(key["tracker"], current, script.m_trackerRole, where + ".tracker");
      script.m_times.push_back(t);
      script.m_keys.push_back(current);
    } catch (const json::exception& e) {
      vt::fail(where, ": ", e.what());
    }
  }
  return script;
}

Sample Script::sample(double t_s) const {
  const auto it = std::upper_bound(m_times.begin(), m_times.end(), t_s);
  if (it == m_times.begin()) return m_keys.front();
  if (it == m_times.end()) return m_keys.back();
  const std::size_t i = std::size_t(it - m_times.begin());
  const float w = float((t_s - m_times[i - 1]) / (m_times[i] - m_times[i - 1]));
  const Sample& a = m_keys[i - 1];
  const Sample& b = m_keys[i];
  Sample out;
  out.head = lerp(a.head, b.head, w);
  for (int h = 0; h < 2; ++h) out.hands[h] = lerp(a.hands[h], b.hands[h], w);
  out.tracker = lerp(a.tracker, b.tracker, w);
  out.trackerTracked = w < 0.5f ? a.trackerTracked : b.trackerTracked;
  return out;
}

}  // namespace xrsim
