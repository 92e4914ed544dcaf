// The conversion matrix (issue #32): every source format to every target and back, lossless
// where both carry the signal (the waveform in HJIF and WAV, the envelope in HJIF, AHAP and
// .haptic) and, where the target cannot, exactly the loss conversionLosses() states.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "test_support.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

namespace files = vt::haptics::files;
using vt::haptics::ActuatorId;

namespace {

// 0.8 s on thumb and index: a waveform (8 kHz, 16-bit values, as recorded) or an envelope
// (frequencies within the normalised scale, 50..450 Hz, where AHAP and .haptic clamp nothing).
files::HapticClip sourceClip(bool pcm) {
  files::HapticClip clip;
  clip.duration_s = 0.8;
  clip.description = "matrix";
  for (ActuatorId id : {ActuatorId::Thumb, ActuatorId::Index}) {
    files::ClipChannel c;
    c.actuator = id;
    const double f = id == ActuatorId::Thumb ? 120.0 : 260.0;
    if (pcm) {
      for (int i = 0; i < 6400; ++i) {
        const double t = i / 8000.0;
        c.pcm.push_back(float(std::lround(0.6 * std::sin(2 * std::numbers::pi * f * t) * std::sin(std::numbers::pi * t / 0.8) * 32767) / 32767.0));
      }
    } else {
      for (int i = 0; i <= 80; ++i) c.envelope.push_back({i * 0.01, float(0.5 + 0.4 * std::sin(i * 0.3)), float(f + 60.0 * std::sin(i * 0.1))});
    }
    clip.channels.push_back(std::move(c));
  }
  if (pcm) clip.sampleRate_hz = 8000;
  return clip;
}

// Writes `clip` as `ext` and reads every file back into one clip (per-actuator files merged).
files::HapticClip through(const files::HapticClip& clip, const std::filesystem::path& dir, const std::string& name, const std::string& ext) {
  const auto written = files::saveHapticFile(clip, dir / (name + ext), true);
  files::HapticClip out;
  for (const auto& path : written) {
    files::HapticClip part = files::loadHapticFile(path);
    out.sampleRate_hz = part.sampleRate_hz;
    out.duration_s = std::max(out.duration_s, part.duration_s);
    for (auto& c : part.channels) out.channels.push_back(std::move(c));
  }
  return out;
}

bool carriesPcm(const std::string& ext, bool sourcePcm) { return (ext == ".hjif" && sourcePcm) || ext == ".wav"; }

}  // namespace

TEST_CASE("Conversion matrix: every format to every other and back, within what each carries", "[files][convert]") {
  const auto dir = vt::test::outputDir("files_convert_matrix");
  const std::vector<std::string> formats = {".hjif", ".ahap", ".haptic", ".wav"};
  for (const bool pcm : {true, false}) {
    const auto original = sourceClip(pcm);
    for (const std::string& from : formats) {
      if (pcm && from != ".hjif" && from != ".wav") continue;  // AHAP and .haptic hold no waveform
      if (!pcm && from == ".wav") continue;                     // WAV holds no envelope
      const auto a = through(original, dir, "a", from);
      for (const std::string& to : formats) {
        INFO((pcm ? "waveform " : "envelope ") << from << " -> " << to << " -> " << from);
        const auto losses = files::conversionLosses(a, files::hapticFormat("clip" + to));
        const auto b = through(a, dir, "b", to);
        const auto c = through(b, dir, "c", from);
        REQUIRE(c.channels.size() == a.channels.size());
        CHECK(c.duration_s == Approx(a.duration_s).margin(0.002));
        for (std::size_t k = 0; k < a.channels.size(); ++k) {
          CHECK(c.channels[k].actuator == a.channels[k].actuator);
          if (carriesPcm(from, pcm) && carriesPcm(to, pcm)) {
            // Lossless but for WAV's 16 bits (these samples are 16-bit values already: exact).
            REQUIRE(c.channels[k].pcm.size() == a.channels[k].pcm.size());
            for (std::size_t i = 0; i < a.channels[k].pcm.size(); i += 7)
              CHECK(c.channels[k].pcm[i] == Approx(a.channels[k].pcm[i]).margin(1.0 / 65534));
          } else if (!carriesPcm(from, pcm) && !carriesPcm(to, pcm)) {
            CHECK(std::none_of(losses.begin(), losses.end(), [](const std::string& l) { return l.find("waveform") != std::string::npos; }));
            for (double t = 0.0; t < 0.8; t += 0.0123) {
              const auto x = files::envelopeAt(a.channels[k].envelope, t), y = files::envelopeAt(c.channels[k].envelope, t);
              CHECK(y.amplitude == Approx(x.amplitude).margin(0.01));
              CHECK(y.frequency_hz == Approx(x.frequency_hz).margin(1.0));
            }
          } else {
            // One side lacks what the other carries: the loss is stated, and what survives is the
            // level over time (the waveform's 1 ms peaks, or a sine synthesised from the envelope).
            CHECK(!losses.empty());
            const auto x = files::channelEnvelope(a.channels[k], a.sampleRate_hz);
            const auto y = files::channelEnvelope(c.channels[k], c.sampleRate_hz);
            double sx = 0.0, sy = 0.0;
            for (double t = 0.1; t < 0.7; t += 0.001) sx += files::envelopeAt(x, t).amplitude, sy += files::envelopeAt(y, t).amplitude;
            CHECK(sy == Approx(sx).epsilon(0.35));
          }
        }
      }
    }
  }
}
