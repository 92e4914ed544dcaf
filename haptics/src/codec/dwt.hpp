#pragma once
// CDF 9/7 wavelet (the JPEG 2000 lifting scheme) with whole-sample symmetric extension, for
// any length >= 2, in place. Coefficients end up in Mallat order: [a_L | d_L | ... | d_1].
#include <span>

namespace vt::haptics::codec {

inline constexpr int kMaxDwtLevels = 5;

/// Levels used for a block of n samples: halve while the approximation keeps >= 2 samples.
int dwtLevels(int n) noexcept;
/// Start index and size of band b in Mallat order: band 0 = approximation, band l = d_(L+1-l).
void dwtBand(int n, int levels, int band, int& start, int& size) noexcept;
/// Forward transform of x (size <= 32) in place.
void dwtForward(std::span<float> x, int levels) noexcept;
/// Inverse of dwtForward.
void dwtInverse(std::span<float> x, int levels) noexcept;

}  // namespace vt::haptics::codec
