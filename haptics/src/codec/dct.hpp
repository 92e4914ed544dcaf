#pragma once
// Orthonormal DCT-II / DCT-III of any length n from a table of cos(pi m / 2n), m < 4n:
// coefficient k is the cosine of frequency k / 2n cycles per sample, so a long block resolves
// the partials of a texture or a sine into a few coefficients. O(n^2), allocation-free.
#include <span>

namespace vt::haptics::codec {

/// Fills table[0..4n) with cos(pi m / 2n).
void makeDctTable(int n, std::span<float> table) noexcept;
/// X = DCT-II(x), n = x.size() = X.size(), table from makeDctTable(n).
void dctForward(std::span<const float> table, std::span<const float> x, std::span<float> X) noexcept;
/// x = DCT-III(X) (the inverse), using only X[0..end) (the rest is zero).
void dctInverse(std::span<const float> table, std::span<const float> X, int end, std::span<float> x) noexcept;

}  // namespace vt::haptics::codec
