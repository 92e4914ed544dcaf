#pragma once
// Tactile rendering: one TactileModel per contact point turns what the finger touches
// into an intensity and a waveform block each haptic tick. Allocation-free, noexcept:
// owned and called by the haptic thread only.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "vt/haptics/vibration_map.hpp"

namespace vt::haptics {

/// How a contact becomes vibration (docs/tactile-rendering.md).
enum class TactileModelKind : std::uint8_t {
  PaperIntensity,   // the paper: level from the map at the contact, on a fixed carrier
  TextureWaveform,  // the map swept along the finger's path at the output rate
  TaxelWaveform,    // recorded per-taxel waveforms played back (TextureWaveform without them)
};

/// The paper's formula, exactly: clamp01(V * (1 + clamp(10 * depth_m, 0, 0.5))) * gain.
float paperIntensity(float mapValue, float depth_m, float gain) noexcept;

/// What one contact point touches during one tick.
struct ContactInput {
  bool inContact = false;
  const VibrationMap* map = nullptr;  // null: touching something that is not tactile
  bool wrap = false;
  glm::vec2 uvStart{0.0f};  // map UV at the previous tick (equal to uvEnd on first contact)
  glm::vec2 uvEnd{0.0f};    // map UV now
  float depth_m = 0.0f;
  float gain = 0.5f;
  /// Optional map scanned across `map`'s direction (same UV grid): blended by the direction
  /// of motion, cos^2 to `map` and sin^2 to this one (docs/tactile-rendering.md).
  const VibrationMap* mapAcross = nullptr;
  glm::vec2 scanDirectionUv{1.0f, 0.0f};  // direction `map` was scanned along, in map pixels
};

/// Renderer settings shared by every contact point of a loop.
struct TactileModelConfig {
  TactileModelKind model = TactileModelKind::PaperIntensity;
  float sampleRate_hz = 8000.0f;
  float ramp_s = 0.002f;       // onset and release time (no clicks)
  float carrier_hz = 250.0f;   // PaperIntensity's waveform (LRA/ERM resonance region)
  float highpass_hz = 20.0f;   // TextureWaveform: removes the map's mean (no motion, no output)
};

/// What one tick produced for one contact point.
struct ContactOutput {
  float intensity = 0.0f;    // 0..1 level (ramped)
  float frequency_hz = 0.0f; // dominant frequency when known, else 0
  float mapValue = 0.0f;     // V at uvEnd (for traces)
  float acrossWeight = 0.0f; // weight of the across map in the blend (0 = along only, 1 = across only)
};

/// Raw samples a TaxelWaveform model keeps to fade out with (one block at most).
inline constexpr std::size_t kMaxReleaseSamples = 32;

/// Per-contact-point tactile model state (envelope, phases, filters). Haptic thread only.
class TactileModel {
 public:
  explicit TactileModel(const TactileModelConfig& config = {}) noexcept;

  /// Fills `block` (one tick of output samples) and returns the tick's levels. Exactly zero
  /// once out of contact and the release ramp has finished.
  ContactOutput render(const ContactInput& input, std::span<float> block) noexcept;
  /// Forgets all state (silence, no ramp).
  void reset() noexcept;

 private:
  float envelopeStep(bool on) noexcept;
  void updateDirection(const ContactInput& input) noexcept;
  float sampleBlend(const ContactInput& input, glm::vec2 uv) const noexcept;

  TactileModelConfig m_config;
  float m_envelope = 0.0f;
  float m_rampStep = 1.0f;
  float m_highpassR = 0.99f;
  double m_carrierPhase = 0.0;
  std::uint32_t m_taxelPhase = 0;
  float m_prevX = 0.0f, m_prevY = 0.0f;  // high-pass state
  bool m_primed = false;                 // high-pass has seen a sample of this contact
  float m_acrossWeight = 0.5f;           // held while the finger rests; 0.5 until it first moves
  // Cached from the last in-contact tick for the release ramp (which must not read the map).
  TactileModelKind m_model = TactileModelKind::PaperIntensity;
  float m_waveAmp = 0.0f;
  float m_level = 0.0f;                  // paper-formula level
  std::array<float, kMaxReleaseSamples> m_lastRaw{};
  std::size_t m_lastRawCount = 0;
};

}  // namespace vt::haptics
