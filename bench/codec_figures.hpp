#pragma once
// The tactile codec's figures for `vt_bench net` (codec_bench.cpp): rate-distortion curves
// (kbit/s, ratio over 16-bit PCM, SNR, SPQI) of signals near the context priors' training
// families and of held-out recordings made with the project's own renderer and acquisition
// pipeline, next to the MPEG haptics reference model measured on exactly those signals.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vt::bench {

/// Block lengths of the rate-distortion curves and of the RM comparison.
inline constexpr int kCurveBlocks_ms[] = {4, 16, 128};

/// Every codec figure as one JSON object (docs/PERFORMANCE.md "Network" says what each is).
/// With VT_MPEG_RM_BIN set to the reference model's bin/ folder (Encoder, Synthesizer), also
/// runs it on the bench's signals (key "mpeg_rm_measured", the content of results/reference/mpeg_rm.json;
/// VT_MPEG_RM_ONLY=NAME,NAME limits that to some signals).
nlohmann::ordered_json codecFigures(bool quick);

/// The RM's rate-distortion points on one 8 kHz signal (mpeg_rm_bench.cpp): {"source", "points":
/// {"4ms": [...], "16ms": [...], "128ms": [...]}}. Measured now by the RM in `rmBin` when given,
/// else read from results/reference/mpeg_rm.json when it holds `name` with the same `digest` (FNV-1a of
/// the samples); null when neither.
nlohmann::ordered_json mpegRmPoints(const std::string& name, const std::vector<float>& samples,
                                    const std::string& digest, const char* rmBin);

}  // namespace vt::bench
