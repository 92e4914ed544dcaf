// Trains the perceptual coder's fixed context priors (haptics/codec/src/context_priors.hpp).
// Regenerate after changing the bit syntax or the encoder's decisions:
//   build/tests/haptics/vt_haptics_tests '[.priors]'   then rebuild, and again (the encoder's
//   choices depend on the priors it starts from; from the second run on, values move by a few
//   1/2048 only). Each model's prior = its share of 0 bits over every use in the training blocks.
// The training signals come from generators defined only here, none of which vt_bench net
// reports (issue #26): chirps with a slow swell, resonant AR(2) Gaussian noise, a bump texture
// (random bumps along a path, not textureHeight's stripes and value noise) swept at changing
// speeds, decaying taps, and a five-actuator set of delayed, scaled bump textures; blocks of 4,
// 8 and 16 ms at qualities 20..80 (the short blocks are where priors matter: a long block's
// models adapt on their own; models those blocks never use keep their previous value). The
// bench's synthetic group (texture sweeps, sines, sum-of-sines noise) is near these families;
// its recorded group (slides rendered by the haptic loop, acquisition waveforms) is far.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "codec_rate.hpp"
#include "../../haptics/codec/src/bit_syntax.hpp"
#include "../../haptics/codec/src/perceptual_coder.hpp"

namespace {

using namespace vt::haptics;
using vt::haptics::codec::syntax::kContextModels;

constexpr int kPriorsSamples = kRate * 4;

std::mt19937 rng(2026);

// Exponential sweep lo -> hi Hz with a slow swell (0.3..1 of `peak`, 0.7 Hz).
std::vector<float> chirp(float lo_hz, float hi_hz, float peak) {
  std::vector<float> out(kPriorsSamples);
  double phase = 0.0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double t = double(i) / double(out.size());
    phase += 2.0 * std::numbers::pi * lo_hz * std::pow(double(hi_hz) / lo_hz, t) / kRate;
    out[i] = float(peak * (0.65 - 0.35 * std::cos(2.0 * std::numbers::pi * 0.7 * double(i) / kRate)) * std::sin(phase));
  }
  return out;
}

// Gaussian noise through a two-pole resonator at f Hz (pole radius r), scaled to `rms`.
std::vector<float> resonantNoise(float f_hz, float r, float rms) {
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<double> y(kPriorsSamples, 0.0);
  const double a1 = 2.0 * r * std::cos(2.0 * std::numbers::pi * f_hz / kRate), a2 = -double(r) * r;
  for (std::size_t i = 2; i < y.size(); ++i) y[i] = unit(rng) + a1 * y[i - 1] + a2 * y[i - 2];
  double energy = 0.0;
  for (double v : y) energy += v * v;
  const double scale = rms / std::sqrt(energy / double(y.size()));
  std::vector<float> out(y.size());
  for (std::size_t i = 0; i < y.size(); ++i) out[i] = float(std::clamp(y[i] * scale, -1.0, 1.0));
  return out;
}

// A path over random bumps (0.2..1 mm wide, spaced 0.3..3 mm), slid at a speed ramping
// v0 -> v1 m/s, mean removed, peak `amplitude`; `delay_m` shifts the path (another finger).
std::vector<float> bumpTexture(float v0, float v1, float amplitude, std::uint32_t seed, double delay_m = 0.0) {
  std::mt19937 bumpRng(seed);
  std::uniform_real_distribution<double> gap(0.0003, 0.003), width(0.0002, 0.001), height(0.3, 1.0);
  std::vector<std::array<double, 3>> bumps;  // centre, width, height
  for (double x = 0.0; x < 0.2; x += gap(bumpRng)) bumps.push_back({x, width(bumpRng), height(bumpRng)});
  std::vector<float> out(kPriorsSamples);
  double x = delay_m;
  std::size_t first = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    x += (v0 + (v1 - v0) * double(i) / double(out.size())) / kRate;
    while (first < bumps.size() && bumps[first][0] + 3 * bumps[first][1] < x) ++first;
    double h = 0.0;
    for (std::size_t b = first; b < bumps.size() && bumps[b][0] - 3 * bumps[b][1] < x; ++b) {
      const double u = (x - bumps[b][0]) / bumps[b][1];
      h += bumps[b][2] * std::exp(-u * u);
    }
    out[i] = float(h);
  }
  double mean = 0.0;
  for (float v : out) mean += v;
  mean /= double(out.size());
  float peak = 1e-9f;
  for (float& v : out) peak = std::max(peak, std::fabs(v -= float(mean)));
  for (float& v : out) v *= amplitude / peak;
  return out;
}

// Taps: decaying f Hz bursts (time constant tau) at random intervals of 50..400 ms.
std::vector<float> taps(float f_hz, float tau_s, float peak) {
  std::uniform_real_distribution<double> interval(0.05, 0.4), level(0.3, 1.0);
  std::vector<float> out(kPriorsSamples, 0.0f);
  for (double start = 0.01; start < double(kPriorsSamples) / kRate; start += interval(rng)) {
    const double a = peak * level(rng);
    for (std::size_t i = std::size_t(start * kRate); i < out.size(); ++i) {
      const double t = double(i) / kRate - start;
      if (t > 6 * tau_s) break;
      out[i] = float(std::clamp(out[i] + a * std::exp(-t / tau_s) * std::sin(2 * std::numbers::pi * f_hz * t), -1.0, 1.0));
    }
  }
  return out;
}

std::vector<std::vector<float>> trainingSignals() {
  std::vector<std::vector<float>> s;
  s.push_back(chirp(30.0f, 600.0f, 0.7f));
  s.push_back(chirp(400.0f, 60.0f, 0.3f));
  s.push_back(resonantNoise(150.0f, 0.97f, 0.2f));
  s.push_back(resonantNoise(400.0f, 0.9f, 0.1f));
  s.push_back(resonantNoise(900.0f, 0.5f, 0.05f));
  s.push_back(bumpTexture(0.03f, 0.15f, 0.6f, 11));
  s.push_back(bumpTexture(0.12f, 0.40f, 0.9f, 12));
  s.push_back(bumpTexture(0.30f, 0.06f, 0.3f, 13));
  s.push_back(taps(180.0f, 0.02f, 0.8f));
  s.push_back(taps(320.0f, 0.005f, 0.5f));
  return s;
}

void count(const std::vector<std::vector<float>>& channels, int length, int quality,
           std::vector<std::array<double, 2>>& counts) {
  const int n = int(channels.size());
  std::vector<float> tables(codec::segmentTablesSize(length)), floats(6 * std::size_t(length));
  std::vector<int> q(static_cast<std::size_t>(length));
  std::vector<float> block(std::size_t(n * length));
  const std::span<float> f(floats);
  const auto L = std::size_t(length);
  const codec::CoderScratch scratch{f.subspan(0, L), f.subspan(L, L), f.subspan(2 * L, L), f.subspan(3 * L, L),
                                    f.subspan(4 * L, 2 * L), q};
  codec::makeSegmentTables(length, tables);
  const codec::BlockShape shape{n, length, kRate, L};
  for (std::size_t start = 0; start + L <= channels[0].size(); start += L) {
    for (int c = 0; c < n; ++c)
      std::copy_n(channels[std::size_t(c)].begin() + std::ptrdiff_t(start), L, block.begin() + std::ptrdiff_t(std::size_t(c) * L));
    codec::countContextUse(tables, codec::perceptualBaseStep(quality), shape, block.data(), scratch, counts);
  }
}

}  // namespace

TEST_CASE("Perceptual coder context priors (regenerates context_priors.hpp)", "[.priors]") {
  std::vector<std::array<double, 2>> counts(kContextModels, {0.0, 0.0});
  const auto signals = trainingSignals();
  std::vector<std::vector<float>> glove;
  for (int c = 0; c < 5; ++c) glove.push_back(bumpTexture(0.05f, 0.2f, 0.8f - 0.12f * float(c), 14, 0.004 * c));
  for (int ms : {4, 8, 16}) {
    for (int quality : {20, 35, 50, 65, 80}) {
      for (const auto& s : signals) count({s}, ms * kRate / 1000, quality, counts);
      count(glove, ms * kRate / 1000, quality, counts);
    }
  }
  std::string table;
  double coded = 0.0;
  for (std::size_t i = 0; i < kContextModels; ++i) {
    const double zeros = counts[i][0], total = counts[i][0] + counts[i][1];
    coded += total;
    const int p = total == 0.0 ? int(codec::syntax::kContextPriors[i])
                               : std::clamp(int(std::lround(2048.0 * (zeros + 0.5) / (total + 1.0))), 32, 2016);
    table += (i % 16 == 0 ? "    " : " ") + std::to_string(p) + (i + 1 == kContextModels ? ",\n" : i % 16 == 15 ? ",\n" : ",");
  }
  REQUIRE(coded > 0.0);
  std::ofstream out(VT_SOURCE_DIR "/haptics/codec/src/context_priors.hpp");
  out << "#pragma once\n"
         "// Starting probabilities of the perceptual coder's context models (P(bit = 0) in 1/2048, in\n"
         "// Contexts::forEachModel order), learned offline: GENERATED by the hidden test \"[.priors]\" in\n"
         "// tests/haptics/codec_priors_tests.cpp (see there for the training signals); do not edit.\n"
         "#include <array>\n#include <cstddef>\n#include <cstdint>\n\n"
         "namespace vt::haptics::codec::syntax {\n\n"
         "inline constexpr std::size_t kContextModels = "
      << kContextModels
      << ";\ninline constexpr std::array<std::uint16_t, kContextModels> kContextPriors = {\n"
      << table << "};\n\n}  // namespace vt::haptics::codec::syntax\n";
  REQUIRE(out.good());
}
