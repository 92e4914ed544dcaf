#include "modes/haptic_options.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "vt/core/error.hpp"

namespace vt::app {
namespace {

haptics::TactileModelKind parseModel(const std::string& text, const std::string& source) {
  if (text == "paper") return haptics::TactileModelKind::PaperIntensity;
  if (text == "texture") return haptics::TactileModelKind::TextureWaveform;
  if (text == "taxel") return haptics::TactileModelKind::TaxelWaveform;
  fail(source, ": tactile model '", text, "' is not paper|texture|taxel");
}

MappingPreset parsePreset(const std::string& text, const std::string& source) {
  if (text == "five") return MappingPreset::FiveFingertips;
  if (text == "vtouching") return MappingPreset::VTouching;
  fail(source, ": mapping '", text, "' is not five|vtouching");
}

}  // namespace

const char* modelName(haptics::TactileModelKind model) noexcept {
  switch (model) {
    case haptics::TactileModelKind::PaperIntensity: return "paper";
    case haptics::TactileModelKind::TextureWaveform: return "texture";
    case haptics::TactileModelKind::TaxelWaveform: return "taxel";
  }
  return "?";
}

const char* presetName(MappingPreset preset) noexcept {
  return preset == MappingPreset::VTouching ? "vtouching" : "five";
}

HapticOptions readHapticOptions(cli::Args& args) {
  HapticOptions options;
  const std::string where = args.command();
  options.rate_hz = float(args.doubleOr("rate", 1000.0));
  options.model = parseModel(args.valueOr("model", "paper"), where + ": --model");
  options.preset = parsePreset(args.valueOr("mapping", "five"), where + ": --mapping");
  options.gain = float(args.doubleOr("gain", 1.0));
  if (!(options.gain >= 0.0f && options.gain <= 4.0f)) fail(where, ": --gain ", options.gain, " out of range 0..4");
  const std::string sampling = args.valueOr("pose-sampling", poseSamplingName(options.sampling));
  if (!parsePoseSampling(sampling.c_str(), options.sampling))
    fail(where, ": --pose-sampling '", sampling, "' is not latest|interpolate|predict");
  const std::string pacing = args.valueOr("haptic-pacing", haptics::loopPacingName(options.pacing));
  if (!haptics::parseLoopPacing(pacing.c_str(), options.pacing))
    fail(where, ": --haptic-pacing '", pacing, "' is not sleep|spin");
  options.hapticLatency_ms = float(args.doubleOr("haptic-latency-ms", 0.0));
  if (!(options.hapticLatency_ms >= 0.0f && options.hapticLatency_ms <= 200.0f))
    fail(where, ": --haptic-latency-ms ", options.hapticLatency_ms, " out of range 0..200");
  try {
    makeHapticConfig(options);  // validates the rate now, with the option's name in the message
  } catch (const Error& e) {
    fail(where, ": --rate ", options.rate_hz, ": ", e.what());
  }
  return options;
}

haptics::HapticConfig makeHapticConfig(const HapticOptions& options) {
  haptics::HapticConfig config = options.preset == MappingPreset::VTouching ? haptics::HapticConfig::vTouching()
                                                                            : haptics::HapticConfig::fiveFingertips();
  config.rate_hz = options.rate_hz;
  config.tactile.model = options.model;
  for (auto& route : config.routes) route.gain = options.gain;
  config.sampling.mode = options.sampling;
  config.sampling.timeout_ns = std::int64_t(double(options.poseTimeout_ms) * 1e6);
  config.outputLatency_ns = std::int64_t(double(options.hapticLatency_ms) * 1e6);
  config.pacing = options.pacing;
  config.validate();
  return config;
}

std::string encodeHapticOptions(const HapticOptions& options) {
  char line[256];
  std::snprintf(line, sizeof line, "rate_hz=%.9g model=%s mapping=%s gain=%.9g pose_timeout_ms=%.9g sampling=%s latency_ms=%.9g",
                double(options.rate_hz), modelName(options.model), presetName(options.preset), double(options.gain),
                double(options.poseTimeout_ms), poseSamplingName(options.sampling), double(options.hapticLatency_ms));
  return line;
}

HapticOptions decodeHapticOptions(const std::string& line, const std::string& source) {
  HapticOptions options;
  char model[32] = {}, mapping[32] = {}, sampling[32] = {};
  if (std::sscanf(line.c_str(), "rate_hz=%f model=%31s mapping=%31s gain=%f pose_timeout_ms=%f sampling=%31s latency_ms=%f",
                  &options.rate_hz, model, mapping, &options.gain, &options.poseTimeout_ms, sampling,
                  &options.hapticLatency_ms) != 7) {
    fail(source, ": config line '", line,
         "': expected rate_hz= model= mapping= gain= pose_timeout_ms= sampling= latency_ms=");
  }
  if (!parsePoseSampling(sampling, options.sampling)) fail(source, ": config line: sampling '", sampling, "' is unknown");
  // sscanf reads "nan" and "inf"; the recording's numbers must be finite and in range like the
  // options, the pose timeout before its conversion to integer nanoseconds (1e30 did not fit).
  if (!(options.gain >= 0.0f && options.gain <= 4.0f) ||
      !(options.poseTimeout_ms >= 0.0f &&
        double(options.poseTimeout_ms) * 1e6 <= double(PoseSamplingConfig::kMaxTimeout_ns)) ||
      !(options.hapticLatency_ms >= 0.0f && options.hapticLatency_ms <= 200.0f)) {
    fail(source, ": config line: gain, pose_timeout_ms or latency_ms is NaN, infinite or out of range");
  }
  options.model = parseModel(model, source);
  options.preset = parsePreset(mapping, source);
  makeHapticConfig(options);
  return options;
}

}  // namespace vt::app
