#pragma once
// CPU images and their PNG/JPEG IO. Loaders throw vt::Error naming the file and the problem.
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace vt {

/// Row-major, top row first, interleaved channels.
template <class Sample>
struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<Sample> pixels;

  Image() = default;
  Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(std::size_t(w) * h * c) {}
  bool empty() const noexcept { return pixels.empty(); }
  Sample& at(int x, int y, int c = 0) noexcept { return pixels[(std::size_t(y) * width + x) * channels + c]; }
  Sample at(int x, int y, int c = 0) const noexcept { return pixels[(std::size_t(y) * width + x) * channels + c]; }
};

using Image8 = Image<std::uint8_t>;
using Image16 = Image<std::uint16_t>;
using ImageF = Image<float>;

/// Loads PNG/JPEG/BMP/TGA as 8-bit with `channels` channels (1..4; converted as needed).
Image8 loadImage8(const std::filesystem::path& path, int channels = 4);
/// Same from bytes in memory; `sourceName` names the source in errors.
Image8 loadImage8(std::span<const std::uint8_t> bytes, const std::string& sourceName, int channels = 4);
/// Loads keeping 16-bit precision when the file has it (8-bit files are scaled by 257).
Image16 loadImage16(const std::filesystem::path& path, int channels);
/// Same from bytes in memory; `sourceName` names the source in errors.
Image16 loadImage16(std::span<const std::uint8_t> bytes, const std::string& sourceName, int channels);
/// True when the encoded image stores 16 bits per sample (a 16-bit PNG).
bool is16BitImage(std::span<const std::uint8_t> bytes);
/// One channel of a file as floats in [0,1] (8- or 16-bit source); channel 0 = red or grey.
ImageF loadChannelAsFloat(const std::filesystem::path& path, int channel = 0);

/// Writes an 8-bit PNG (1..4 channels). Throws vt::Error naming the file on failure.
void savePng(const std::filesystem::path& path, const Image8& image);
/// Writes a 16-bit PNG (1..4 channels).
void savePng16(const std::filesystem::path& path, const Image16& image);
/// The bytes of an 8-bit / 16-bit PNG file of `image` (1..4 channels), for embedding.
std::vector<std::uint8_t> encodePng(const Image8& image);
std::vector<std::uint8_t> encodePng16(const Image16& image);

}  // namespace vt
