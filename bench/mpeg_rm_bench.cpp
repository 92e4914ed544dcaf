// The MPEG haptics reference model (ISO/IEC 23090-31 reference software, "RM") on the codec
// bench's signals (codec_figures.hpp). The RM is never part of this repository: it is built
// outside it (docs/PERFORMANCE.md "Network" says how) and named by VT_MPEG_RM_BIN; a run with it
// writes "mpeg_rm_measured", which is stored as results/reference/mpeg_rm.json, and later runs read their
// RM points from there for the signals whose samples still hash the same.
//
// Per signal and block length (4, 16, 128 ms = RM wavelet blocks of 32, 128, 1024 samples at
// 8 kHz), wavelet-only (-cf 0 --disable-vectorial: one wavelet band over the whole spectrum, no
// low-frequency split), for six wavelet bit budgets (-bu) per block length spanning about
// 10..40 dB: the signal as a float32 WAV -> Encoder -> HJIF (payload = its wavelet streams, the
// coded bits without container or packet headers) -> Synthesizer -> 16-bit WAV at 8 kHz,
// compared with the samples by SNR and SPQI.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <iterator>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "codec_figures.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/codec/spqi.hpp"
#include "vt/haptics/codec/test_signals.hpp"
#include "vt/haptics/files/haptic_clip.hpp"

namespace vt::bench {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

constexpr int kRate = 8000;
// Per kCurveBlocks_ms entry (the RM caps a budget at (log2(length) - 1) x 15: 60, 90, 135).
constexpr int kBudgets[][6] = {{3, 5, 8, 12, 18, 26}, {4, 7, 11, 16, 23, 32}, {6, 10, 15, 22, 32, 45}};

const json& storedRm() {
  static const json stored = [] {
    const fs::path path = fs::path(VT_ASSETS_DIR) / "../results/reference/mpeg_rm.json";
    std::ifstream in(path);
    return in ? json::parse(in) : json();
  }();
  return stored;
}

void writeFloatWav(const fs::path& path, const std::vector<float>& samples) {
  const auto u32 = [](std::string& s, std::uint32_t v) { for (int i = 0; i < 4; ++i) s.push_back(char((v >> (8 * i)) & 0xFF)); };
  const auto u16 = [](std::string& s, std::uint16_t v) { for (int i = 0; i < 2; ++i) s.push_back(char((v >> (8 * i)) & 0xFF)); };
  const auto bytes = std::uint32_t(samples.size() * 4);
  std::string h = "RIFF";
  u32(h, 36 + bytes);
  h += "WAVEfmt ";
  u32(h, 16);
  u16(h, 3);  // IEEE float
  u16(h, 1);
  u32(h, kRate);
  u32(h, kRate * 4);
  u16(h, 4);
  u16(h, 32);
  h += "data";
  u32(h, bytes);
  std::ofstream out(path, std::ios::binary);
  out.write(h.data(), std::streamsize(h.size()));
  out.write(reinterpret_cast<const char*>(samples.data()), std::streamsize(bytes));
  if (!out) fail("mpeg rm: cannot write ", path.string());
}

void run(const std::string& command) {
  const int status = std::system((command + " >/dev/null 2>&1").c_str());
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) fail("mpeg rm: '", command, "' failed");
}

// Bytes of the wavelet streams in an HJIF file (base64, 6 bits a character).
double payloadBytes(const fs::path& hjif) {
  std::ifstream in(hjif);
  const json file = json::parse(in);
  double bytes = 0.0;
  for (const auto& perception : file.at("perceptions"))
    for (const auto& channel : perception.at("channels"))
      for (const auto& band : channel.at("bands"))
        for (const auto& effect : band.at("effects"))
          if (effect.contains("wavelet_stream")) bytes += double(effect["wavelet_stream"].get<std::string>().size()) * 6.0 / 8.0;
  return bytes;
}

json measure(const std::vector<float>& samples, const char* rmBin) {
  const fs::path dir = fs::temp_directory_path() / ("vt_mpeg_rm_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string bin = rmBin, in = (dir / "in.wav").string();
  writeFloatWav(in, samples);
  const double seconds = double(samples.size()) / kRate;
  json points;
  for (std::size_t b = 0; b < std::size(kCurveBlocks_ms); ++b) {
    const int block_ms = kCurveBlocks_ms[b];
    json curve = json::array();
    for (int budget : kBudgets[b]) {
      run(bin + "/Encoder -f " + in + " -cf 0 --disable-vectorial -bl " + std::to_string(block_ms * kRate / 1000) + " -bu " +
          std::to_string(budget) + " -o " + (dir / "out.hjif").string());
      run(bin + "/Synthesizer -fs 8000 -f " + (dir / "out.hjif").string() + " -o " + (dir / "dec.wav").string());
      std::vector<float> decoded = haptics::files::loadRecording("", dir / "dec.wav").channels.at(0).pcm;
      decoded.resize(samples.size(), 0.0f);
      curve.push_back({{"budget", budget},
                       {"payload_kbps", payloadBytes(dir / "out.hjif") * 8.0 / seconds / 1000.0},
                       {"snr_db", haptics::snr_db(samples, decoded)},
                       {"spqi", haptics::spqi(samples, decoded)}});
    }
    points[std::to_string(block_ms) + "ms"] = curve;
  }
  fs::remove_all(dir);
  return points;
}

}  // namespace

json mpegRmPoints(const std::string& name, const std::vector<float>& samples, const std::string& digest, const char* rmBin) {
  if (rmBin) return {{"source", "measured in this run"}, {"points", measure(samples, rmBin)}};
  const json& stored = storedRm();
  if (!stored.contains("signals") || !stored["signals"].contains(name)) return nullptr;
  const json& entry = stored["signals"][name];
  if (entry.value("digest", "") != digest)
    return {{"source", "results/reference/mpeg_rm.json was measured on other samples (digest " + entry.value("digest", "") + "): not used"}};
  return {{"source", "results/reference/mpeg_rm.json"}, {"points", entry["points"]}};
}

}  // namespace vt::bench
