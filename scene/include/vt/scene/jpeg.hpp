#pragma once
// JPEG in memory, for the server's video stream: encode a rendered frame, decode a received one.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vt/scene/image.hpp"

namespace vt {

/// Largest JPEG decodeJpeg accepts, in bytes and in pixels (a video frame, not a photo).
inline constexpr std::size_t kMaxJpegBytes = 16u << 20;
inline constexpr long long kMaxJpegPixels = 4096LL * 4096;

/// Baseline JPEG of a 1..4-channel 8-bit image (alpha is dropped), quality 1..100.
/// Throws vt::Error on an empty image or a bad quality. Any thread.
std::vector<std::uint8_t> encodeJpeg(const Image8& image, int quality);

/// Decodes a JPEG to RGBA8. Throws vt::Error naming `source` when the bytes are not a JPEG,
/// are corrupt, or exceed kMaxJpegBytes / kMaxJpegPixels. Any thread.
Image8 decodeJpeg(std::span<const std::uint8_t> bytes, const std::string& source);

}  // namespace vt
