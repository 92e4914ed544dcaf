#pragma once
// The Spectral Perceptual Quality Index (SPQI), a full-reference vibrotactile quality metric:
// A. Noll, M. Hofbauer, E. Muschter, S.-C. Li, E. Steinbach, "Automated Quality Assessment for
// Compressed Vibrotactile Signals Using Multi-Method Assessment Fusion", IEEE Haptics Symposium
// 2022, doi:10.1109/HAPTICS52432.2022.9765599. Steps and constants as the authors publish them
// in their reference implementation (vibromaf, linked from the paper; docs/protocol.md
// "Perceptual quality" says what was checked and how):
//   1. both signals cut into whole blocks of 512 samples (a partial last block is dropped);
//   2. per block an orthonormal DCT-II, |X_k| in dB minus the perceptual threshold T(f_k) of
//      spqiThreshold_db, back to power: P_k = |X_k|^2 / 10^(T_k / 10);
//   3. per block D = 10 log10(sum_k |P_ref,k - P_dist,k| / (sum_k P_ref,k + eps));
//   4. per block score (1 - tanh(0.3 D + 2)) / 2; SPQI = the mean over blocks.
// 1 = identical, towards 0 = perceptually far apart. Lives beside the codec because it uses the
// codec's DCT-II (haptics/codec/src/dct.hpp). Any thread; allocates its working buffers.
#include <span>
#include <vector>

namespace vt::haptics {

/// Samples per SPQI block.
inline constexpr int kSpqiBlock = 512;

/// The metric's perceptual threshold in dB at DCT bin k of a blockLength-point block,
/// f_k = k * sampleRate / (2 blockLength - 1): |62 (log10(f/550 + a) / log10 a)^2| - 77,
/// a = 1 - 250/550, held at its value from the first bin where it turns positive on.
std::vector<double> spqiThreshold_db(int blockLength, double sampleRate_hz);

/// SPQI of `distorted` against `reference` (0..1). `distorted` longer than the reference is
/// cut to its length. Throws vt::Error when the reference is shorter than one block or
/// `distorted` shorter than the reference.
double spqi(std::span<const float> reference, std::span<const float> distorted, double sampleRate_hz = 8000.0);

}  // namespace vt::haptics
