// The tactile codec's figures for `vt_bench net` (codec_figures.hpp). Two groups of signals:
//  - near_training: the synthetic generators of haptics/codec/test_signals.hpp (texture sweeps,
//    sines, sum-of-sines noise), near the families the context priors were trained on
//    (tests/haptics/codec_priors_tests.cpp: chirps, resonant noise, bump textures, taps) but
//    none of them;
//  - held_out: vibrations recorded with the project's own tools, far from any training signal:
//    the example slide rendered by the haptic loop with the texture and the paper model, and
//    acquisition waveforms of synthetic scans (the stylus accelerometer through the pipeline).
// Per signal: the rate-distortion curve (quality 10..90, default 50 marked) at 4, 16 and 128 ms
// with SNR and SPQI (haptics/codec/include/vt/haptics/codec/spqi.hpp), quality 50 at every
// block length, and the MPEG haptics reference model (RM) on the same samples: its points from
// results/reference/mpeg_rm.json, used only when the stored digest matches the signal, and this codec's
// bits at each point's SNR.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <string>
#include <vector>

#include "codec_figures.hpp"
#include "modes/touch_pipeline.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/haptics/codec/test_signals.hpp"
#include "vt/haptics/haptic_loop.hpp"
#include "vt/haptics/haptic_scene.hpp"
#include "vt/scene/loaders.hpp"
#include "vt/scene/pose_history.hpp"
#include "vt/scene/trajectory.hpp"
// The scan signals need the acquisition library, which a VT_ONLY build may leave out.
#if __has_include("vt/acquisition/waveforms.hpp")
#include "vt/acquisition/pipeline.hpp"
#include "vt/acquisition/synthetic.hpp"
#include "vt/acquisition/waveforms.hpp"
#define VT_CODEC_BENCH_SCANS 1
#endif

namespace vt::bench {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

constexpr int kRate = 8000;
constexpr int kDefaultQuality = 50;
constexpr int kQualities[] = {10, 30, 50, 70, 90};

struct CodecSignal {
  std::string name, group, origin;
  std::vector<std::vector<float>> channels;  // one per actuator, equal lengths
};

/// FNV-1a over the samples' bytes: a stored RM figure counts only for these exact samples.
std::string digest(const std::vector<float>& samples) {
  std::uint64_t h = 14695981039346656037ull;
  for (float v : samples) {
    unsigned char bytes[sizeof v];
    std::memcpy(bytes, &v, sizeof v);
    for (unsigned char b : bytes) h = (h ^ b) * 1099511628211ull;
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

std::vector<CodecSignal> nearTrainingSignals(int samples) {
  const std::string near = "near_training";
  return {{"texture_sweep", near, "textureSweepSignal 0.05->0.25 m/s", {haptics::textureSweepSignal(0.05f, 0.25f, 0.8f, samples, kRate)}},
          {"texture_slow", near, "textureSweepSignal 0.02->0.08 m/s", {haptics::textureSweepSignal(0.02f, 0.08f, 0.8f, samples, kRate)}},
          {"sine_80hz", near, "sineSignal 80 Hz", {haptics::sineSignal(80.0f, 0.5f, samples, kRate)}},
          {"sine_250hz", near, "sineSignal 250 Hz", {haptics::sineSignal(250.0f, 0.5f, samples, kRate)}},
          {"band_noise_50_800hz", near, "bandNoiseSignal 50-800 Hz", {haptics::bandNoiseSignal(50.0f, 800.0f, 0.2f, samples, kRate, 7)}},
          {"white_noise", near, "bandNoiseSignal 0-4000 Hz", {haptics::bandNoiseSignal(0.0f, 4000.0f, 0.2f, samples, kRate, 8)}}};
}

/// The example slide (assets/trajectories/slide.csv over the assets' dataset scene, five
/// fingertips, 1 kHz ticks, 8 kHz) rendered by a stepped touch pipeline as `vtouching serve
/// --model ...` renders it: one waveform per actuator. Empty when the assets are missing.
std::vector<std::vector<float>> renderSlide(haptics::TactileModelKind model) {
  const fs::path assets = VT_ASSETS_DIR;
  if (!fs::exists(assets / "trajectories/slide.csv")) return {};
  const Trajectory trajectory = loadTrajectory(assets / "trajectories/slide.csv");
  auto scene = std::make_shared<const Scene>(loadDatasetScene(assets / "dataset"));
  const app::LoadedScene loaded{scene, haptics::makeHapticScene(scene), "assets"};
  ManualClock clock;
  app::TouchPipelineSpec spec;  // five fingertips at 1 kHz, 8 kHz output: the defaults
  spec.haptic.model = model;
  spec.sinks.glove = "none";
  spec.drive = app::TouchDrive::Stepped;
  spec.clock = &clock;
  app::TouchPipeline pipeline(loaded, spec);
  std::vector<std::vector<float>> out(pipeline.config().actuatorCount());
  pipeline.onFrame([&out](const haptics::ActuatorFrame& frame) {
    for (std::size_t c = 0; c < out.size(); ++c)
      out[c].insert(out[c].end(), frame.block[c].begin(), frame.block[c].begin() + frame.blockLength);
  });
  const auto period_ns = std::int64_t(std::llround(1e9 / double(pipeline.config().rate_hz)));
  const double t0 = trajectory.keys.front().t_s;
  for (std::int64_t t_ns = 0; t_ns < std::int64_t(trajectory.duration_s() * 1e9); t_ns += period_ns) {
    HandPose pose = trajectory.poseAt(t0 + double(t_ns) * 1e-9);
    pose.t_ns = t_ns;
    pipeline.publishPose(pose);
    clock.set(t_ns);
    pipeline.tick(t_ns);
    pipeline.drain();
  }
  return out;
}

std::vector<float> loudest(const std::vector<std::vector<float>>& channels, int samples) {
  const auto energy = [](const std::vector<float>& s) { return std::inner_product(s.begin(), s.end(), s.begin(), 0.0); };
  const auto& best = *std::max_element(channels.begin(), channels.end(),
                                       [&](const auto& a, const auto& b) { return energy(a) < energy(b); });
  return {best.begin(), best.begin() + std::min<std::ptrdiff_t>(samples, std::ptrdiff_t(best.size()))};
}

#ifdef VT_CODEC_BENCH_SCANS
/// Acquisition waveforms of a synthetic scan (`vtouching acquire --synthetic KIND` with
/// waveforms, 6 lines): the taxel cells of each scan line in order, i.e. the stylus
/// accelerometer along the line as the pipeline cut it, 1 g rest and mean removed, peak 0.8.
std::vector<float> scanWaveform(acq::SyntheticKind kind, int samples) {
  const fs::path dir = fs::temp_directory_path() / ("vt_codec_bench_" + std::to_string(::getpid()));
  acq::SyntheticOptions options;
  options.kind = kind;
  options.lines = 6;
  acq::writeSyntheticScan(options, dir, 0, true);
  acq::AcquireOptions acquireOptions;
  acquireOptions.keepSamples = true;
  const acq::WaveformGrid grid = acq::measureWaveforms(acq::acquire(acq::loadScan(dir), acquireOptions));
  fs::remove_all(dir);
  std::vector<float> out;
  for (int col = 0; col < grid.width && int(out.size()) < samples; ++col)
    for (int row = 0; row < grid.height; ++row) {
      const std::size_t cell = std::size_t(row) * std::size_t(grid.width) + std::size_t(col);
      if (!grid.measured[cell]) continue;
      const auto first = grid.samples.begin() + std::ptrdiff_t(cell * std::size_t(grid.samplesPerCell));
      out.insert(out.end(), first, first + grid.samplesPerCell);
    }
  out.resize(std::min(out.size(), std::size_t(samples)));
  const double mean = std::accumulate(out.begin(), out.end(), 0.0) / double(std::max<std::size_t>(out.size(), 1));
  float peak = 1e-9f;
  for (float& v : out) peak = std::max(peak, std::fabs(v -= float(mean)));
  for (float& v : out) v *= 0.8f / peak;
  return out;
}
#endif

std::vector<CodecSignal> heldOutSignals(int samples) {
  const std::string held = "held_out";
  std::vector<CodecSignal> out;
  const auto texture = renderSlide(haptics::TactileModelKind::TextureWaveform);
  if (!texture.empty()) {
    out.push_back({"slide_texture_loudest", held, "example slide, --model texture, loudest actuator", {loudest(texture, samples)}});
    std::vector<std::vector<float>> five;
    for (const auto& c : texture) five.emplace_back(c.begin(), c.begin() + std::min<std::ptrdiff_t>(samples, std::ptrdiff_t(c.size())));
    out.push_back({"slide_texture_5ch", held, "example slide, --model texture, all 5 actuators in one block", five});
    out.push_back({"slide_paper_loudest", held, "example slide, --model paper (250 Hz carrier), loudest actuator",
                   {loudest(renderSlide(haptics::TactileModelKind::PaperIntensity), samples)}});
  }
#ifdef VT_CODEC_BENCH_SCANS
  out.push_back({"scan_relief_tile", held, "acquisition waveforms, synthetic relief_ceramic_tile scan",
                 {scanWaveform(acq::SyntheticKind::ReliefCeramicTile, samples)}});
  out.push_back({"scan_notebook_cover", held, "acquisition waveforms, synthetic notebook_cover scan",
                 {scanWaveform(acq::SyntheticKind::NotebookCover, samples)}});
#endif
  return out;
}

haptics::CodecConfig configFor(const CodecSignal& signal, int block_ms, int quality) {
  haptics::CodecConfig config;
  config.channels = int(signal.channels.size());
  config.block_ms = block_ms;
  config.quality = quality;
  return config;
}

json point(const haptics::CodecReport& r, int quality) {
  return {{"quality", quality}, {"kbps", r.bitrate_kbps}, {"ratio", r.ratio}, {"snr_db", r.snr_db}, {"spqi", r.spqi}};
}

/// This codec at the lowest quality that reaches `snr_db` (SNR rises with quality: bisection).
json atSnr(haptics::CodecConfig config, const std::vector<std::vector<float>>& channels, double snr_db) {
  int lo = 0, hi = 100;
  while (lo < hi) {
    config.quality = (lo + hi) / 2;
    if (haptics::evaluateCodec(config, channels).snr_db >= snr_db) hi = config.quality;
    else lo = config.quality + 1;
  }
  config.quality = lo;
  return point(haptics::evaluateCodec(config, channels), lo);
}

std::string ms(int block_ms) { return std::to_string(block_ms) + "ms"; }

json signalFigures(const CodecSignal& signal, const char* rmBin) {
  json out = {{"group", signal.group}, {"origin", signal.origin}, {"channels", signal.channels.size()},
              {"samples", signal.channels[0].size()}, {"digest", digest(signal.channels[0])}};
  json curves;
  for (int block_ms : kCurveBlocks_ms) {
    json curve = json::array();
    for (int quality : kQualities) curve.push_back(point(haptics::evaluateCodec(configFor(signal, block_ms, quality), signal.channels), quality));
    curves[ms(block_ms)] = curve;
  }
  out["rate_distortion"] = curves;
  json q50;
  for (int block_ms : haptics::kCodecBlockLengths_ms) {
    const auto r = haptics::evaluateCodec(configFor(signal, block_ms, kDefaultQuality), signal.channels);
    json row = point(r, kDefaultQuality);
    row["encode_us_per_block"] = r.encode_us_per_block;
    row["decode_us_per_block"] = r.decode_us_per_block;
    q50[ms(block_ms)] = row;
  }
  out["default_quality_per_block_length"] = q50;
  if (signal.channels.size() > 1) return out;
  json rm = mpegRmPoints(signal.name, signal.channels[0], out["digest"], rmBin);
  if (rm.is_null()) return out;
  // This codec at the SNR of each RM point (the RM's useful range: 10..40 dB).
  for (int block_ms : kCurveBlocks_ms) {
    if (!rm.contains("points")) break;
    for (auto& p : rm["points"][ms(block_ms)]) {
      const double snr = p["snr_db"];
      if (snr >= 10.0 && snr <= 40.0) p["ours_at_same_snr"] = atSnr(configFor(signal, block_ms, 0), signal.channels, snr);
    }
  }
  out["mpeg_rm"] = rm;
  return out;
}

}  // namespace

json codecFigures(bool quick) {
  const int samples = quick ? kRate : kRate * 10;
  std::vector<CodecSignal> signals = nearTrainingSignals(samples);
  for (auto& s : heldOutSignals(samples)) signals.push_back(std::move(s));
  const char* rmBin = std::getenv("VT_MPEG_RM_BIN");
  json out = {{"sample_rate_hz", kRate}, {"default_quality", kDefaultQuality}, {"qualities", kQualities},
              {"curve_block_ms", kCurveBlocks_ms}, {"seconds_per_signal", samples / kRate}};
  json groups = {{"near_training", json::array()}, {"held_out", json::array()}};
  json perSignal, measuredRm;
  // VT_MPEG_RM_ONLY=a,b: run the RM on these signals only (a long measurement split over runs).
  std::string only;
  if (const char* list = std::getenv("VT_MPEG_RM_ONLY")) only.append(",").append(list).append(",");
  for (const auto& signal : signals) {
    groups[signal.group].push_back(signal.name);
    const bool runRm = rmBin && (only.empty() || only.find(std::string(",").append(signal.name).append(",")) != std::string::npos);
    perSignal[signal.name] = signalFigures(signal, runRm ? rmBin : nullptr);
    if (runRm && perSignal[signal.name].contains("mpeg_rm")) {
      const json& figures = perSignal[signal.name];
      measuredRm[signal.name] = {{"digest", figures["digest"]}, {"samples", figures["samples"]}, {"points", figures["mpeg_rm"]["points"]}};
      for (auto& [block, points] : measuredRm[signal.name]["points"].items())
        for (auto& p : points) p.erase("ours_at_same_snr");
    }
  }
  out["groups"] = groups;
  out["signals"] = perSignal;
  // Issue #21's 4 ms goal: texture sweep at >= 20:1 over 16-bit PCM with SNR >= 20 dB.
  out["texture_sweep_4ms_at_20db"] = atSnr(configFor(signals[0], 4, 0), signals[0].channels, 20.0);
  // Five actuators at once (the glove): the same texture on each, one block for all.
  auto five = signals[0];
  five.channels.assign(5, signals[0].channels[0]);
  out["texture_sweep_5ch_ratio"] = haptics::evaluateCodec(configFor(five, 4, kDefaultQuality), five.channels).ratio;
  if (rmBin) out["mpeg_rm_measured"] = measuredRm;
  return out;
}

}  // namespace vt::bench
