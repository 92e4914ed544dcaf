#include "vt/haptics/tactile_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vt::haptics {

float paperIntensity(float mapValue, float depth_m, float gain) noexcept {
  const float depthFactor = 1.0f + std::clamp(10.0f * depth_m, 0.0f, 0.5f);
  return std::clamp(mapValue * depthFactor, 0.0f, 1.0f) * gain;
}

TactileModel::TactileModel(const TactileModelConfig& config) noexcept : m_config(config) {
  const float fs = std::max(config.sampleRate_hz, 1.0f);
  m_rampStep = 1.0f / std::max(config.ramp_s * fs, 1.0f);
  // One-pole DC blocker: y[n] = x[n] - x[n-1] + R y[n-1], cutoff ~ (1 - R) fs / 2pi.
  m_highpassR = std::clamp(1.0f - 2.0f * std::numbers::pi_v<float> * config.highpass_hz / fs, 0.0f, 0.9999f);
}

void TactileModel::reset() noexcept {
  m_envelope = 0.0f;
  m_carrierPhase = 0.0;
  m_taxelPhase = 0;
  m_prevX = m_prevY = 0.0f;
  m_primed = false;
  m_model = m_config.model;
  m_waveAmp = 0.0f;
  m_level = 0.0f;
  m_lastRawCount = 0;
  m_acrossWeight = 0.5f;
}

void TactileModel::updateDirection(const ContactInput& input) noexcept {
  if (!input.mapAcross) return;
  // Motion in map pixels (maps are square-pixelled images of the object), against the scan axis.
  const glm::vec2 d = (input.uvEnd - input.uvStart) * glm::vec2(float(input.map->width()), float(input.map->height()));
  const float length = glm::length(d);
  if (!(length > 1e-3f) || !std::isfinite(length)) return;  // resting: keep the last direction
  const float c = glm::dot(d / length, input.scanDirectionUv);
  m_acrossWeight = std::clamp(1.0f - c * c, 0.0f, 1.0f);
}

float TactileModel::sampleBlend(const ContactInput& input, glm::vec2 uv) const noexcept {
  const float along = input.map->sample(uv, input.wrap);
  if (!input.mapAcross) return along;
  return along + (input.mapAcross->sample(uv, input.wrap) - along) * m_acrossWeight;
}

float TactileModel::envelopeStep(bool on) noexcept {
  m_envelope = on ? std::min(1.0f, m_envelope + m_rampStep) : std::max(0.0f, m_envelope - m_rampStep);
  return m_envelope;
}

ContactOutput TactileModel::render(const ContactInput& input, std::span<float> block) noexcept {
  const bool on = input.inContact && input.map && !input.map->empty();
  if (!on && m_envelope == 0.0f) {
    std::fill(block.begin(), block.end(), 0.0f);
    reset();
    return {};
  }
  const std::size_t n = block.size();
  ContactOutput out;
  if (on) {
    m_model = m_config.model;
    if (m_model == TactileModelKind::TaxelWaveform && input.map->waveforms().empty()) m_model = TactileModelKind::TextureWaveform;
    const float depthFactor = 1.0f + std::clamp(10.0f * input.depth_m, 0.0f, 0.5f);
    m_waveAmp = 2.0f * input.gain * depthFactor;  // gain 0.5 at the surface = unity
    updateDirection(input);
    out.acrossWeight = input.mapAcross ? m_acrossWeight : 0.0f;
    out.mapValue = sampleBlend(input, input.uvEnd);
    m_level = paperIntensity(out.mapValue, input.depth_m, input.gain);
  }
  // Release (not on) never touches the map: the snapshot it came from may be gone by now.
  // Each model fades from cached state: the carrier at the held level, the high-pass output
  // decaying, or the last raw taxel samples repeated.
  if (m_model == TactileModelKind::PaperIntensity) {
    const double dphi = 2.0 * std::numbers::pi * double(m_config.carrier_hz) / double(m_config.sampleRate_hz);
    for (std::size_t k = 0; k < n; ++k) {
      block[k] = m_level * envelopeStep(on) * float(std::sin(m_carrierPhase));
      m_carrierPhase = std::fmod(m_carrierPhase + dphi, 2.0 * std::numbers::pi);
    }
    if (n == 0) envelopeStep(on);
    out.intensity = m_level * m_envelope;
    out.frequency_hz = m_config.carrier_hz;
    return out;
  }

  float peak = 0.0f;
  const VibrationMap* map = on ? input.map : nullptr;
  for (std::size_t k = 0; k < n; ++k) {
    // The contact point moves uvStart -> uvEnd during the tick; sample k sits at (k+1)/n.
    const glm::vec2 uv = on ? glm::mix(input.uvStart, input.uvEnd, float(k + 1) / float(n)) : glm::vec2(0.0f);
    float s;
    if (m_model == TactileModelKind::TaxelWaveform) {
      if (map) {
        const std::span<const float> wave = map->waveform(map->taxel(uv, input.wrap));
        s = wave[m_taxelPhase % wave.size()];
        m_taxelPhase = (m_taxelPhase + 1) % std::uint32_t(wave.size());
        m_lastRaw[k % m_lastRaw.size()] = s;
        m_lastRawCount = std::min(n, m_lastRaw.size());
      } else {
        s = m_lastRawCount ? m_lastRaw[k % m_lastRawCount] : 0.0f;
      }
    } else {
      const float x = map ? sampleBlend(input, uv) : m_prevX;  // released: standing still
      if (!m_primed) m_prevX = x, m_primed = true;
      s = x - m_prevX + m_highpassR * m_prevY;
      m_prevX = x;
      m_prevY = s;
    }
    block[k] = std::clamp(s * m_waveAmp, -1.0f, 1.0f) * envelopeStep(on);
    peak = std::max(peak, std::abs(block[k]));
  }
  if (n == 0) envelopeStep(on);
  // Level devices get the waveform's peak (texture: silent at rest) or the taxel's RMS level.
  out.intensity = m_model == TactileModelKind::TaxelWaveform ? m_level * m_envelope : std::min(peak, 1.0f);
  return out;
}

}  // namespace vt::haptics
