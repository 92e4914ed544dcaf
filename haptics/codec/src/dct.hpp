#pragma once
// Orthonormal DCT-II / DCT-III of any length n: coefficient k is the cosine of frequency
// k / 2n cycles per sample, so a long block resolves the partials of a texture or a sine into
// a few coefficients. Powers of two go through an n-point complex FFT (Makhoul's reordering,
// O(n log n)); other lengths use a cosine table (O(n^2)). Allocation-free.
#include <span>

namespace vt::haptics::codec {

/// Floats of the table of length n (makeDctTable fills them).
inline constexpr int dctTableSize(int n) noexcept { return 4 * n; }
/// Fills table[0..dctTableSize(n)).
void makeDctTable(int n, std::span<float> table) noexcept;
/// X = DCT-II(x), n = x.size() = X.size(); `work` holds 2n floats.
void dctForward(std::span<const float> table, std::span<const float> x, std::span<float> X,
                std::span<float> work) noexcept;
/// x = DCT-III(X) (the inverse), using only X[0..end) (the rest is zero); `work` holds 2n floats.
void dctInverse(std::span<const float> table, std::span<const float> X, int end, std::span<float> x,
                std::span<float> work) noexcept;

}  // namespace vt::haptics::codec
