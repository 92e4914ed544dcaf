#pragma once
// Haptic settings the user picks (command line or HUD) and the HapticConfig they make.
#include <string>

#include "cli.hpp"
#include "vt/haptics/haptic_config.hpp"

namespace vt::app {

/// Contact-point -> actuator mapping presets.
enum class MappingPreset { FiveFingertips, VTouching };

struct HapticOptions {
  float rate_hz = 1000.0f;
  haptics::TactileModelKind model = haptics::TactileModelKind::PaperIntensity;
  MappingPreset preset = MappingPreset::FiveFingertips;
  float gain = 1.0f;  // route gain on top of each material's own tactile gain
  /// How each tick samples the hand from the pose history (docs/tactile-rendering.md, "Time").
  PoseSampling sampling = PoseSampling::Predict;
  /// The glove's (or audio output's) delay: ticks sample the hand this much ahead.
  float hapticLatency_ms = 0.0f;
  /// No pose this recent: no hand. Covers display-rate sources down to 5 Hz (a software
  /// renderer under load) for every mode alike.
  float poseTimeout_ms = 200.0f;
  /// How the loop thread waits between ticks (not recorded: it changes timing, not what is felt).
  haptics::LoopPacing pacing = haptics::LoopPacing::Sleep;
};

/// Reads --rate HZ, --model paper|texture|taxel, --mapping five|vtouching, --gain G,
/// --pose-sampling latest|interpolate|predict, --haptic-latency-ms MS, --haptic-pacing sleep|spin.
HapticOptions readHapticOptions(cli::Args& args);
/// The loop configuration for these options (validated; throws vt::Error).
haptics::HapticConfig makeHapticConfig(const HapticOptions& options);

const char* modelName(haptics::TactileModelKind model) noexcept;
const char* presetName(MappingPreset preset) noexcept;

/// One line "rate_hz=1000 model=paper mapping=five gain=1 pose_timeout_ms=200 sampling=predict
/// latency_ms=0" and its parser (recordings).
std::string encodeHapticOptions(const HapticOptions& options);
HapticOptions decodeHapticOptions(const std::string& line, const std::string& source);

}  // namespace vt::app
