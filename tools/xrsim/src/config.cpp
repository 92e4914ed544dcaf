#include "config.hpp"

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "vt/core/error.hpp"
#include "vt/xr/openxr_ext_haptic_parametric.hpp"
#include "vt/xr/openxr_fb_haptics.hpp"

namespace xrsim {
namespace {

const char* env(const char* name) {
  const char* value = std::getenv(name);
  return (value && *value) ? value : nullptr;
}

std::uint64_t parseCount(const std::string& text, const std::string& source) {
  try {
    std::size_t used = 0;
    const long long value = std::stoll(text, &used);
    if (used == text.size() && value >= 0) return std::uint64_t(value);
  } catch (const std::exception&) {
  }
  vt::fail(source, ": '", text, "' is not a non-negative integer");
}

double parseNumber(const std::string& text, const std::string& source) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size()) return value;
  } catch (const std::exception&) {
  }
  vt::fail(source, ": '", text, "' is not a number");
}

bool parseBool(const std::string& text, const std::string& source) {
  if (text == "1" || text == "true" || text == "on") return true;
  if (text == "0" || text == "false" || text == "off") return false;
  vt::fail(source, ": '", text, "' is not a boolean (1/0/true/false)");
}

Failure parseFailure(const std::string& text, const std::string& source) {
  if (text == "none") return Failure::None;
  if (text == "no-hmd") return Failure::NoHmd;
  if (text == "refuse-session") return Failure::RefuseSession;
  vt::fail(source, ": '", text, "' is not one of none, no-hmd, refuse-session");
}

// One setting as text, from the JSON file or the environment (which wins).
template <class Apply>
void setting(const nlohmann::json& file, const std::string& fileSource, const char* key,
             const char* envName, Apply apply) {
  if (file.contains(key)) {
    const auto& value = file[key];
    apply(value.is_string() ? value.get<std::string>() : value.dump(), fileSource + " field '" + key + "'");
  }
  if (const char* text = env(envName)) apply(std::string(text), std::string("environment ") + envName);
}

}  // namespace

Config loadConfig() {
  Config config;
  nlohmann::json file = nlohmann::json::object();
  std::string fileSource = "xrsim config";
  if (const char* path = env("XRSIM_CONFIG")) {
    fileSource = std::string("xrsim config '") + path + "'";
    std::ifstream in(path);
    if (!in) vt::fail(fileSource, ": cannot open");
    try {
      file = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      vt::fail(fileSource, ": invalid JSON: ", e.what());
    }
    if (!file.is_object()) vt::fail(fileSource, ": expected a JSON object");
  }
  auto count = [](std::uint64_t& out) { return [&out](const std::string& t, const std::string& s) { out = parseCount(t, s); }; };
  auto integer = [](int& out) {
    return [&out](const std::string& t, const std::string& s) {
      const std::uint64_t v = parseCount(t, s);
      if (v == 0 || v > 8192) vt::fail(s, ": ", v, " is outside 1..8192");
      out = int(v);
    };
  };
  auto number = [](auto& out) { return [&out](const std::string& t, const std::string& s) { out = decltype(out + 0)(parseNumber(t, s)); }; };
  auto boolean = [](bool& out) { return [&out](const std::string& t, const std::string& s) { out = parseBool(t, s); }; };
  auto text = [](auto& out) { return [&out](const std::string& t, const std::string&) { out = t; }; };

  setting(file, fileSource, "width", "XRSIM_WIDTH", integer(config.width));
  setting(file, fileSource, "height", "XRSIM_HEIGHT", integer(config.height));
  setting(file, fileSource, "ipd_m", "XRSIM_IPD_M", number(config.ipd_m));
  setting(file, fileSource, "tan_half_fov_x", "XRSIM_TAN_HALF_FOV_X", number(config.tanHalfFovX));
  setting(file, fileSource, "tan_half_fov_y", "XRSIM_TAN_HALF_FOV_Y", number(config.tanHalfFovY));
  setting(file, fileSource, "frame_rate_hz", "XRSIM_FRAME_RATE_HZ", number(config.frameRate_hz));
  setting(file, fileSource, "realtime", "XRSIM_REALTIME", boolean(config.realtime));
  setting(file, fileSource, "stop_after_frames", "XRSIM_FRAMES", count(config.stopAfterFrames));
  setting(file, fileSource, "lose_after_frames", "XRSIM_LOSE_AFTER_FRAMES", count(config.loseAfterFrames));
  setting(file, fileSource, "recenter_after_frames", "XRSIM_RECENTER_AFTER_FRAMES", count(config.recenterAfterFrames));
  setting(file, fileSource, "lose_instance", "XRSIM_LOSE_INSTANCE", boolean(config.loseInstance));
  std::uint64_t restarts = 0;
  setting(file, fileSource, "restarts", "XRSIM_RESTARTS", count(restarts));
  config.restarts = int(restarts);
  setting(file, fileSource, "output_dir", "XRSIM_OUTPUT_DIR", text(config.outputDir));
  setting(file, fileSource, "save_every", "XRSIM_SAVE_EVERY", count(config.saveEvery));
  setting(file, fileSource, "script", "XRSIM_SCRIPT", text(config.scriptPath));
  setting(file, fileSource, "hand_tracking", "XRSIM_HAND_TRACKING", boolean(config.handTracking));
  setting(file, fileSource, "hand_rate_hz", "XRSIM_HAND_RATE_HZ", number(config.handRate_hz));
  setting(file, fileSource, "profile", "XRSIM_PROFILE", text(config.profile));
  setting(file, fileSource, "depth_layers", "XRSIM_DEPTH_LAYERS", boolean(config.depthLayers));
  setting(file, fileSource, "haptic_pcm", "XRSIM_HAPTIC_PCM", boolean(config.hapticPcm));
  setting(file, fileSource, "haptic_pcm_capacity", "XRSIM_HAPTIC_PCM_CAPACITY", number(config.hapticPcmCapacity));
  setting(file, fileSource, "haptic_envelope", "XRSIM_HAPTIC_ENVELOPE", boolean(config.hapticEnvelope));
  setting(file, fileSource, "haptic_parametric", "XRSIM_HAPTIC_PARAMETRIC", boolean(config.hapticParametric));
  setting(file, fileSource, "haptic_pcm_hands", "XRSIM_HAPTIC_PCM_HANDS", text(config.hapticPcmHands));
  setting(file, fileSource, "failure", "XRSIM_FAILURE",
          [&](const std::string& t, const std::string& s) { config.failure = parseFailure(t, s); });
  setting(file, fileSource, "validation", "XRSIM_VALIDATION", boolean(config.validation));

  if (!(config.hapticPcmCapacity >= 0.0 && config.hapticPcmCapacity <= XR_MAX_HAPTIC_PCM_BUFFER_SIZE_FB))
    vt::fail(fileSource, ": haptic_pcm_capacity ", config.hapticPcmCapacity, " is outside 0..",
             XR_MAX_HAPTIC_PCM_BUFFER_SIZE_FB, " (0 = the whole buffer)");
  if (!(config.handRate_hz >= 0.0 && config.handRate_hz <= 1000.0))
    vt::fail(fileSource, ": hand_rate_hz ", config.handRate_hz, " is outside 0..1000 (0 = every requested time)");
  if (!(config.frameRate_hz > 1.0 && config.frameRate_hz < 1000.0))
    vt::fail(fileSource, ": frame_rate_hz ", config.frameRate_hz, " is outside 1..1000");
  if (!(config.tanHalfFovX > 0.01f && config.tanHalfFovY > 0.01f))
    vt::fail(fileSource, ": field of view tangents must be positive");
  if (!config.outputDir.empty()) std::filesystem::create_directories(config.outputDir);
  return config;
}

}  // namespace xrsim
