#include "vt/haptics/codec/psychohaptic.hpp"

#include <algorithm>
#include <cmath>

namespace vt::haptics {

namespace {
constexpr float kSlopeBelow_db_per_octave = 12.0f;
constexpr float kSlopeAbove_db_per_octave = 12.0f;
constexpr float kFlatBelow_hz = 40.0f;
}  // namespace

float vibrotactileThreshold_db(float frequency_hz) noexcept {
  const float f = std::max(frequency_hz, kFlatBelow_hz);
  const float octaves = std::log2(f / kPeakSensitivity_hz);
  return octaves < 0.0f ? -octaves * kSlopeBelow_db_per_octave : octaves * kSlopeAbove_db_per_octave;
}

}  // namespace vt::haptics
