// Apple Haptic and Audio Pattern (AHAP), as Apple's Core Haptics documentation describes it.
#include <algorithm>
#include <cmath>

#include "ahap_intensity.hpp"
#include "json_fields.hpp"
#include "json_writer.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

namespace vt::haptics::files {
namespace {

using nlohmann::json;

constexpr double kMaxEvent_s = 30.0;    // Core Haptics' limit for one continuous event
constexpr std::size_t kMaxCurvePoints = 16;  // control points per ParameterCurve
constexpr double kTransient_s = 0.01;   // how long a transient event drives the glove

// Curves of at most 16 points each, consecutive curves sharing their joint point; the control
// points' times are relative to their curve's Time.
void appendCurves(JsonWriter& w, const char* id, const std::vector<std::pair<double, double>>& points) {
  for (std::size_t start = 0; start < points.size();) {
    const std::size_t end = std::min(points.size(), start + kMaxCurvePoints);
    w.beginObject().key("ParameterCurve").beginObject().member("ParameterID", id).member("Time", points[start].first);
    w.key("ParameterCurveControlPoints").beginArray();
    for (std::size_t i = start; i < end; ++i)
      w.beginObject().member("Time", points[i].first - points[start].first).member("ParameterValue", points[i].second).endObject();
    w.endArray().endObject().endObject();
    if (end == points.size()) break;
    start = end - 1;
  }
}

double curveAt(const std::vector<std::pair<double, double>>& points, double t, double fallback) {
  if (points.empty()) return fallback;
  if (t <= points.front().first) return points.front().second;
  if (t >= points.back().first) return points.back().second;
  const auto it = std::upper_bound(points.begin(), points.end(), t, [](double v, const auto& p) { return v < p.first; });
  const auto& [t1, v1] = *it;
  const auto& [t0, v0] = *(it - 1);
  return t1 > t0 ? v0 + (v1 - v0) * (t - t0) / (t1 - t0) : v1;
}

// The envelope as intensity points (ahap_intensity.hpp): every segment cut into pieces equally
// spaced in intensity, each within kAhapInterpolationError of the envelope's line.
std::vector<EnvelopePoint> intensityEnvelope(const std::vector<EnvelopePoint>& envelope) {
  std::vector<EnvelopePoint> out;
  for (std::size_t i = 0; i < envelope.size(); ++i) {
    const EnvelopePoint& p = envelope[i];
    const double s1 = std::sqrt(std::max(double(p.amplitude), 0.0));
    if (i > 0) {
      const EnvelopePoint& q = envelope[i - 1];
      const double a0 = std::max(double(q.amplitude), 0.0), a1 = s1 * s1;
      const double s0 = std::sqrt(a0);
      const double f0 = normaliseFrequency(q.frequency_hz), f1 = normaliseFrequency(p.frequency_hz);
      const int pieces = ahapIntensityPieces(q.amplitude, p.amplitude, p.t_s - q.t_s);
      for (int k = 1; k < pieces; ++k) {  // pieces > 1 only where a1 != a0
        const double s = s0 + (s1 - s0) * k / pieces;
        const double w = (s * s - a0) / (a1 - a0);  // where on the segment the amplitude is s^2
        out.push_back({q.t_s + w * (p.t_s - q.t_s), float(s), frequencyFromNormalised(float(f0 + w * (f1 - f0)))});
      }
    }
    out.push_back({p.t_s, float(s1), p.frequency_hz});
  }
  return out;
}

}  // namespace

int ahapIntensityPieces(float a0, float a1, double duration_s) noexcept {
  // A piece whose intensities differ by d plays at most d^2 / 4 below its line.
  const double d = std::abs(std::sqrt(std::max(double(a1), 0.0)) - std::sqrt(std::max(double(a0), 0.0)));
  const double pieces = std::min(std::ceil(d / (2.0 * std::sqrt(kAhapInterpolationError))), std::floor(duration_s * 1000.0));
  return pieces > 1.0 ? int(pieces) : 1;
}

std::string writeAhap(const HapticClip& clip, std::size_t channel) {
  // Core Haptics' intensity is perceptual (the drive amplitude is its square) and its curves are
  // linear in intensity: points are inserted and simplified there, so the curve between kept
  // points stays faithful. An intensity error e is an amplitude error of at most 2e + e^2: half
  // the simplification's tolerance in intensity keeps the amplitude within kAhapInterpolationError
  // of the inserted points, so within 0.002 of the envelope in all.
  const auto envelope =
      simplifyEnvelope(intensityEnvelope(channelEnvelope(clip.channels.at(channel), clip.sampleRate_hz)),
                       float(kAhapInterpolationError / 2.0));
  const double duration = std::max({clip.duration_s, envelope.empty() ? 0.0 : envelope.back().t_s, kShortestWrittenClip_s});
  if (duration > kMaxClip_s) fail("AHAP: a clip of ", duration, " s is over the ", kMaxClip_s, " s limit (split it first)");
  std::string out;
  JsonWriter w(out);
  w.beginObject().member("Version", 1.0).key("Metadata").beginObject().member("Project", "V-Touching")
      .member("Description", str(clip.description, " (", actuatorName(clip.channels[channel].actuator), ")")).endObject();
  w.key("Pattern").beginArray();
  for (double t = 0.0; t < duration; t += kMaxEvent_s) {
    w.beginObject().key("Event").beginObject().member("Time", t).member("EventType", "HapticContinuous")
        .member("EventDuration", std::min(kMaxEvent_s, duration - t)).key("EventParameters").beginArray();
    w.beginObject().member("ParameterID", "HapticIntensity").member("ParameterValue", 1.0).endObject();
    w.beginObject().member("ParameterID", "HapticSharpness").member("ParameterValue", 0.0).endObject();
    w.endArray().endObject().endObject();
  }
  std::vector<std::pair<double, double>> intensity, sharpness;
  for (const EnvelopePoint& p : envelope) {
    intensity.emplace_back(p.t_s, double(p.amplitude));
    sharpness.emplace_back(p.t_s, normaliseFrequency(p.frequency_hz));  // unknown: 0.5, the nominal frequency
  }
  appendCurves(w, "HapticIntensityControl", intensity);
  appendCurves(w, "HapticSharpnessControl", sharpness);
  w.endArray().endObject();
  return out;
}

HapticClip readAhap(std::string_view textIn, const std::string& source, ActuatorId actuator) {
  const json doc = parse(textIn, source, {{"ParameterCurveControlPoints", {"Time", "ParameterValue"}}});
  number(doc, "Version", source, 1, 2);
  const json& pattern = array(doc, "Pattern", source);
  struct Event {
    double t, duration, intensity, sharpness;
  };
  std::vector<Event> events;
  std::vector<std::pair<double, double>> intensityCurve, sharpnessCurve;
  double end = 0.0;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    const std::string where = str(source, ": Pattern[", i, "]");
    const json& entry = pattern[i];
    if (!entry.is_object() || entry.size() != 1) fail(where, " must hold exactly one of Event, ParameterCurve, Parameter");
    if (entry.contains("Event")) {
      const json& e = entry["Event"];
      const std::string ew = where + ".Event";
      const std::string type = text(e, "EventType", ew);
      Event ev{number(e, "Time", ew, 0, kMaxClip_s), 0.0, 1.0, 0.0};
      if (type == "HapticContinuous") ev.duration = number(e, "EventDuration", ew, 0, kMaxEvent_s);
      else if (type == "HapticTransient") ev.duration = kTransient_s;
      else if (type == "AudioContinuous" || type == "AudioCustom") continue;  // sound, not touch
      else fail(ew, ".EventType '", type, "' is not HapticContinuous, HapticTransient, AudioContinuous or AudioCustom");
      const json& params = array(e, "EventParameters", ew);
      for (std::size_t k = 0; k < params.size(); ++k) {
        const std::string pw = str(ew, ".EventParameters[", k, "]");
        const std::string id = text(params[k], "ParameterID", pw);
        const double value = number(params[k], "ParameterValue", pw, 0, 1);
        if (id == "HapticIntensity") ev.intensity = value;
        else if (id == "HapticSharpness") ev.sharpness = value;
      }
      if (ev.t + ev.duration > kMaxClip_s) fail(ew, ": ends at ", ev.t + ev.duration, " s, past the ", kMaxClip_s, " s limit");
      end = std::max(end, ev.t + ev.duration);
      events.push_back(ev);
    } else if (entry.contains("ParameterCurve")) {
      const json& c = entry["ParameterCurve"];
      const std::string cw = where + ".ParameterCurve";
      const std::string id = text(c, "ParameterID", cw);
      const double t0 = number(c, "Time", cw, 0, kMaxClip_s);
      const Records points(c, "ParameterCurveControlPoints", 2, cw);
      if (points.size() > kMaxCurvePoints) fail(cw, ".ParameterCurveControlPoints has ", points.size(), " points (at most 16)");
      auto& curve = id == "HapticIntensityControl" ? intensityCurve : sharpnessCurve;
      for (std::size_t k = 0; k < points.size(); ++k) {
        const double t = t0 + points.number(k, 0, "Time", 0, kMaxClip_s);
        const double value = points.number(k, 1, "ParameterValue", id == "HapticSharpnessControl" ? -1 : 0, 1);
        if (id == "HapticIntensityControl" || id == "HapticSharpnessControl") curve.emplace_back(t, value);
      }
    } else if (!entry.contains("Parameter")) {
      fail(where, " must hold exactly one of Event, ParameterCurve, Parameter");
    }
  }
  if (events.empty()) fail(source, ": no haptic event in Pattern");
  if (events.size() > 100000) fail(source, ": more than 100000 events in Pattern");
  auto byTime = [](const auto& a, const auto& b) { return a.first < b.first; };
  std::stable_sort(intensityCurve.begin(), intensityCurve.end(), byTime);
  std::stable_sort(sharpnessCurve.begin(), sharpnessCurve.end(), byTime);
  HapticClip clip;
  clip.description = doc.contains("Metadata") && doc["Metadata"].is_object() && doc["Metadata"].contains("Description") &&
                             doc["Metadata"]["Description"].is_string()
                         ? doc["Metadata"]["Description"].get<std::string>() : "AHAP pattern";
  clip.duration_s = end;
  ClipChannel channel;
  channel.actuator = actuator;
  // Sample the pattern every millisecond (events painted over their span, later ones on top),
  // then keep what a linear envelope needs.
  const auto samples = std::size_t(std::floor(end * 1000.0 + 1e-6)) + 1;
  std::vector<double> eventIntensity(samples, 0.0), eventSharpness(samples, 0.0);
  for (const Event& e : events) {
    const auto from = std::size_t(std::ceil(e.t * 1000.0 - 1e-6));
    const auto to = std::min(samples - 1, std::size_t(std::floor((e.t + e.duration) * 1000.0 + 1e-6)));
    for (std::size_t i = from; i <= to; ++i) {
      eventIntensity[i] = std::max(eventIntensity[i], e.intensity), eventSharpness[i] = e.sharpness;
    }
  }
  for (std::size_t i = 0; i < samples; ++i) {
    const double t = double(i) * 0.001;
    const double intensity = eventIntensity[i] * curveAt(intensityCurve, t, 1.0);
    const double sharpness = std::clamp(eventSharpness[i] + curveAt(sharpnessCurve, t, 0.0), 0.0, 1.0);
    channel.envelope.push_back({t, float(intensity * intensity), frequencyFromNormalised(float(sharpness))});
  }
  channel.envelope = simplifyEnvelope(channel.envelope, 0.001f);
  clip.channels.push_back(std::move(channel));
  return clip;
}

}  // namespace vt::haptics::files
