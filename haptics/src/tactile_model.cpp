#include "vt/haptics/tactile_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vt::haptics {

float paperIntensity(float mapValue, float depth_m, float gain) noexcept {
  const float depthFactor = 1.0f + std::clamp(10.0f * depth_m, 0.0f, 0.5f);
  return std::clamp(mapValue * depthFactor, 0.0f, 1.0f) * gain;
}

TactileRenderer::TactileRenderer(const RendererConfig& config) noexcept : m_config(config) {
  const float fs = std::max(config.sampleRate_hz, 1.0f);
  m_rampStep = 1.0f / std::max(config.ramp_s * fs, 1.0f);
  // One-pole DC blocker: y[n] = x[n] - x[n-1] + R y[n-1], cutoff ~ (1 - R) fs / 2pi.
  m_highpassR = std::clamp(1.0f - 2.0f * std::numbers::pi_v<float> * config.highpass_hz / fs, 0.0f, 0.9999f);
}

void TactileRenderer::reset() noexcept {
  m_envelope = 0.0f;
  m_carrierPhase = 0.0;
  m_taxelPhase = 0;
  m_prevX = m_prevY = 0.0f;
  m_primed = false;
  m_held = {};
}

float TactileRenderer::envelopeStep(bool on) noexcept {
  m_envelope = on ? std::min(1.0f, m_envelope + m_rampStep) : std::max(0.0f, m_envelope - m_rampStep);
  return m_envelope;
}

ContactOutput TactileRenderer::render(const ContactInput& input, std::span<float> block) noexcept {
  const bool on = input.inContact && input.map && !input.map->empty();
  if (on) m_held = input;
  if (!on && m_envelope == 0.0f) {
    std::fill(block.begin(), block.end(), 0.0f);
    reset();
    return {};
  }
  // During release the finger has left the surface: replay the last contact, standing still.
  ContactInput in = on ? input : m_held;
  if (!on) in.uvStart = in.uvEnd;
  const VibrationMap& map = *in.map;
  const float depthFactor = 1.0f + std::clamp(10.0f * in.depth_m, 0.0f, 0.5f);
  const float waveAmp = 2.0f * in.gain * depthFactor;  // gain 0.5 at the surface = unity
  ContactOutput out;
  out.mapValue = map.sample(in.uvEnd, in.wrap);
  const std::size_t n = block.size();
  TactileModel model = m_config.model;
  if (model == TactileModel::TaxelWaveform && map.waveforms().empty()) model = TactileModel::TextureWaveform;

  if (model == TactileModel::PaperIntensity) {
    const float level = paperIntensity(out.mapValue, in.depth_m, in.gain);
    const double dphi = 2.0 * std::numbers::pi * double(m_config.carrier_hz) / double(m_config.sampleRate_hz);
    for (std::size_t k = 0; k < n; ++k) {
      block[k] = level * envelopeStep(on) * float(std::sin(m_carrierPhase));
      m_carrierPhase = std::fmod(m_carrierPhase + dphi, 2.0 * std::numbers::pi);
    }
    if (n == 0) envelopeStep(on);
    out.intensity = level * m_envelope;
    out.frequency_hz = m_config.carrier_hz;
    return out;
  }

  float peak = 0.0f;
  for (std::size_t k = 0; k < n; ++k) {
    // The contact point moves uvStart -> uvEnd during the tick; sample k sits at (k+1)/n.
    const glm::vec2 uv = glm::mix(in.uvStart, in.uvEnd, float(k + 1) / float(n));
    float s;
    if (model == TactileModel::TaxelWaveform) {
      const std::span<const float> wave = map.waveform(map.taxel(uv, in.wrap));
      s = wave[m_taxelPhase % wave.size()];
      m_taxelPhase = (m_taxelPhase + 1) % std::uint32_t(wave.size());
    } else {
      const float x = map.sample(uv, in.wrap);
      if (!m_primed) m_prevX = x, m_primed = true;
      s = x - m_prevX + m_highpassR * m_prevY;
      m_prevX = x;
      m_prevY = s;
    }
    block[k] = std::clamp(s * waveAmp, -1.0f, 1.0f) * envelopeStep(on);
    peak = std::max(peak, std::abs(block[k]));
  }
  if (n == 0) envelopeStep(on);
  // Level devices get the waveform's peak (texture: silent at rest) or the taxel's RMS level.
  out.intensity = model == TactileModel::TaxelWaveform
                      ? paperIntensity(out.mapValue, in.depth_m, in.gain) * m_envelope
                      : std::min(peak, 1.0f);
  return out;
}

}  // namespace vt::haptics
