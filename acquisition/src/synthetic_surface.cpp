// Procedural objects modelled on the paper's eight: a roughness pattern (what the stylus
// feels) and an albedo that shows the same structure (what the camera sees).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "vt/acquisition/synthetic.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/demo_scene.hpp"

namespace vt::acq {
namespace {

constexpr double kPi = std::numbers::pi;

constexpr std::string_view kNames[] = {"pattern_board", "relief_ceramic_tile", "plastic_grid", "smooth_ceramic_tile",
                                       "notebook_cover", "gift_box", "red_envelope", "plastic_cutting_board"};
// Vibration (g) where roughness = 1, chosen so the statistics land near the paper's Table I.
constexpr double kPeak_g[] = {0.65, 0.7, 0.55, 0.06, 0.35, 0.45, 0.4, 0.3};

double smoothstep(double e0, double e1, double x) noexcept {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}
// Smooth value noise in [0,1] with features of about `scale_mm` (reuses the scene's noise).
double noise(double u_mm, double v_mm, double scale_mm) noexcept {
  return patternValue(Pattern::Speckle, float(u_mm / scale_mm / 48.0), float(v_mm / scale_mm / 48.0));
}
// Union of two features in [0,1] without a kink (std::max has one): the stylus' acceleration
// follows the height's second derivative, so the roughness must stay smooth.
double softOr(double a, double b) noexcept { return a + b - a * b; }
double fract(double x) noexcept { return x - std::floor(x); }
// Closeness to a band of half-width `w` around 0 of a distance d: 1 inside, smooth edge.
double band(double d, double w) noexcept { return 1.0 - smoothstep(w, w + 0.6, std::abs(d)); }

struct Flower {
  double s, t, r;
};
constexpr Flower kFlowers[] = {{0.3, 0.35, 0.16}, {0.68, 0.58, 0.22}, {0.22, 0.8, 0.11}, {0.82, 0.18, 0.1}};

// Signed distance (mm) to a five-petal outline; negative inside.
double petalDistance(const Flower& f, double u, double v, double size) noexcept {
  const double dx = u - f.s * size, dy = v - f.t * size;
  const double r = f.r * size * (0.75 + 0.25 * std::cos(5 * std::atan2(dy, dx)));
  return std::hypot(dx, dy) - r;
}

// Closeness in [0,1] to a deterministic set of knife scratches, each fading out at its ends
// (everything stays smooth: a step in height would be an unbounded acceleration).
double scratches(double u, double v, double w, double h) noexcept {
  double best = 0;
  const double half = 0.25 * std::max(w, h);
  for (int i = 0; i < 24; ++i) {
    const double a = 2.4 * i + 0.3, px = fract(0.37 * i + 0.11) * w, py = fract(0.61 * i + 0.29) * h;
    const double along = (u - px) * std::cos(a) + (v - py) * std::sin(a);
    const double across = -(u - px) * std::sin(a) + (v - py) * std::cos(a);
    best = softOr(best, band(across, 0.5) * (1.0 - smoothstep(0.8 * half, half, std::abs(along))));
  }
  return best;
}

}  // namespace

std::span<const std::string_view> syntheticKindNames() noexcept { return kNames; }

std::string_view kindName(SyntheticKind kind) noexcept { return kNames[int(kind)]; }

SyntheticKind parseSyntheticKind(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kNames); ++i) {
    if (kNames[i] == name) return SyntheticKind(i);
  }
  std::string all;
  for (auto n : kNames) all += (all.empty() ? "" : ", ") + std::string(n);
  fail("unknown synthetic kind '", name, "' (expected one of: ", all, ")");
}

SyntheticSurface makeSurface(SyntheticKind kind, double width_m, double height_m, double speed_m_s) {
  SyntheticSurface s;
  s.kind = kind;
  s.width_m = width_m;
  s.height_m = height_m;
  const double k = 2 * kPi / s.wavelength_m;
  // Mean |z''| over a period is (2/pi) A v^2 k^2; solve for A at the kind's peak vibration.
  s.peakAmplitude_m = kPeak_g[int(kind)] * kStandardGravity_m_s2 * kPi / (2 * speed_m_s * speed_m_s * k * k);
  return s;
}

double SyntheticSurface::roughness(double u_m, double v_m) const noexcept {
  const double u = u_m * 1e3, v = v_m * 1e3, w = width_m * 1e3, h = height_m * 1e3, size = std::min(w, h);
  switch (kind) {
    case SyntheticKind::PatternBoard: {
      double outline = 0;
      for (const Flower& f : kFlowers) outline = softOr(outline, band(petalDistance(f, u, v, size), 0.9));
      return softOr(0.05 + 0.04 * noise(u, v, 3), outline);
    }
    case SyntheticKind::ReliefCeramicTile: {
      const double p = 18;
      const double d1 = (fract((u + v) / p) - 0.5) * p * 0.7071, d2 = (fract((u - v) / p) - 0.5) * p * 0.7071;
      const double cu = (std::round(u / p) * p), cv = (std::round(v / p) * p);
      const double ring = band(std::hypot(u - cu, v - cv) - 3.0, 0.6);
      return 0.06 + 0.94 * softOr(softOr(band(d1, 0.7), band(d2, 0.7)), ring);
    }
    case SyntheticKind::PlasticGrid: {
      const double p = 8;
      const double bar = softOr(band((fract(u / p) - 0.5) * p, 1.2), band((fract(v / p) - 0.5) * p, 1.2));
      return 0.06 + 0.94 * bar;
    }
    case SyntheticKind::SmoothCeramicTile: return 0.1 + 0.25 * noise(u, v, 7);
    case SyntheticKind::NotebookCover: {
      const double n = noise(u, v, 1.6);
      return 0.2 + 0.8 * n * n;
    }
    case SyntheticKind::GiftBox: {
      const double stripe = band((fract((u + 0.6 * v) / 14) - 0.5) * 14, 2.2);
      const double dot = band(std::hypot(fract(u / 9) - 0.5, fract(v / 9) - 0.5) * 9 - 1.2, 0.1);
      return 0.15 + 0.85 * softOr(stripe, 0.7 * dot);
    }
    case SyntheticKind::RedEnvelope: {
      const double r = std::hypot(u - w / 2, v - h / 2);
      const double ring = band(r - 0.32 * size, 1.5);
      const double box = (1 - smoothstep(0.18 * size, 0.18 * size + 1, std::abs(u - w / 2))) *
                         (1 - smoothstep(0.18 * size, 0.18 * size + 1, std::abs(v - h / 2)));
      const double bars = box * softOr(band((fract(u / 6) - 0.5) * 6, 0.9), band((fract(v / 10) - 0.5) * 10, 0.9));
      return 0.08 + 0.92 * softOr(ring, bars);
    }
    case SyntheticKind::PlasticCuttingBoard:
      return 0.3 + 0.6 * scratches(u, v, w, h) + 0.1 * noise(u, v, 2);
  }
  return 0;
}

double SyntheticSurface::surfaceHeight_m(double u_m, double v_m) const noexcept {
  // The fine texture runs along Y (the scan direction) with a phase that varies per X.
  return peakAmplitude_m * roughness(u_m, v_m) * std::sin(2 * kPi * v_m / wavelength_m + 37.0 * u_m);
}

std::array<float, 3> SyntheticSurface::albedo(double u_m, double v_m) const noexcept {
  const double u = u_m * 1e3, v = v_m * 1e3, size = std::min(width_m, height_m) * 1e3;
  const double r = roughness(u_m, v_m);
  const double grain = 0.94 + 0.06 * noise(u, v, 0.7);
  auto mix = [&](std::array<double, 3> a, std::array<double, 3> b, double t) {
    return std::array<float, 3>{float((a[0] + (b[0] - a[0]) * t) * grain), float((a[1] + (b[1] - a[1]) * t) * grain),
                                float((a[2] + (b[2] - a[2]) * t) * grain)};
  };
  switch (kind) {
    case SyntheticKind::PatternBoard: {
      double inside = 0;
      for (const Flower& f : kFlowers) inside = std::max(inside, 1.0 - smoothstep(-1.0, 0.5, petalDistance(f, u, v, size)));
      const auto base = mix({0.55, 0.6, 0.55}, {0.86, 0.84, 0.88}, inside);
      const double edge = std::clamp((r - 0.2) / 0.8, 0.0, 1.0);
      return mix({base[0], base[1], base[2]}, {0.45, 0.48, 0.45}, 0.5 * edge);
    }
    case SyntheticKind::ReliefCeramicTile: return mix({0.86, 0.8, 0.66}, {0.55, 0.45, 0.32}, (r - 0.06) / 0.94);
    case SyntheticKind::PlasticGrid: return mix({0.12, 0.13, 0.15}, {0.92, 0.92, 0.94}, (r - 0.06) / 0.94);
    case SyntheticKind::SmoothCeramicTile: {
      const double vein = band(std::sin(u / 9 + 4 * noise(u, v, 15)) * 8, 0.3);
      return mix({0.93, 0.93, 0.91}, {0.7, 0.72, 0.74}, 0.6 * vein);
    }
    case SyntheticKind::NotebookCover: return mix({0.08, 0.12, 0.3}, {0.2, 0.27, 0.55}, r);
    case SyntheticKind::GiftBox: return mix({0.65, 0.06, 0.1}, {0.9, 0.72, 0.25}, (r - 0.15) / 0.85);
    case SyntheticKind::RedEnvelope: return mix({0.72, 0.04, 0.05}, {0.95, 0.78, 0.3}, (r - 0.08) / 0.92);
    case SyntheticKind::PlasticCuttingBoard: return mix({0.9, 0.9, 0.86}, {0.62, 0.64, 0.6}, (r - 0.3) / 0.7);
  }
  return {0, 0, 0};
}

}  // namespace vt::acq
