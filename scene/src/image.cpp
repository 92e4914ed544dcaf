#include "vt/scene/image.hpp"

#include <libdeflate.h>
#include <stb_image.h>

#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <string>

#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/core/output_file.hpp"

namespace vt {
namespace {

struct StbFree {
  void operator()(void* p) const noexcept { stbi_image_free(p); }
};

void checkChannels(int channels, const std::string& source) {
  if (channels < 1 || channels > 4) fail(source, ": requested ", channels, " channels (expected 1..4)");
}

std::string describe(const std::filesystem::path& path) { return "image '" + path.string() + "'"; }

void putBigEndian32(std::uint8_t* out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out[i] = std::uint8_t(v >> (24 - 8 * i));
}

// PNG's Paeth predictor of a byte from its left (a), upper (b) and upper-left (c) neighbours.
std::uint8_t paeth(int a, int b, int c) {
  const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
  return std::uint8_t(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

// The PNG file of 8- or 16-bit samples: every row Paeth-filtered, one IDAT holding libdeflate's
// zlib stream at level 1. Measured on acquisition's maps and photos and on the published
// dataset's (docs/PERFORMANCE.md, "Acquisition"): Paeth is within 0.5 % of the per-row best-of-five
// filter at half its cost, and levels above 1 save 1 - 5 % of bytes for 2 - 3x the time.
template <class Sample>
std::vector<std::uint8_t> encodePngFile(const Image<Sample>& image, const std::string& source) {
  checkChannels(image.channels, source);
  if (image.empty()) fail(source, ": refusing to encode an empty image");
  constexpr int kBytes = int(sizeof(Sample));
  const std::size_t pixelBytes = std::size_t(image.channels) * kBytes;
  const std::size_t rowBytes = std::size_t(image.width) * pixelBytes;
  const std::size_t rowSamples = std::size_t(image.width) * image.channels;
  std::vector<std::uint8_t> filtered((rowBytes + 1) * std::size_t(image.height));
  // PNG stores samples big-endian: 16-bit rows are swapped into two alternating row buffers.
  std::vector<std::uint8_t> swapped(kBytes == 1 ? 0 : 2 * rowBytes);
  const std::uint8_t* previous = nullptr;
  for (int y = 0; y < image.height; ++y) {
    const Sample* samples = image.pixels.data() + std::size_t(y) * rowSamples;
    const std::uint8_t* row = reinterpret_cast<const std::uint8_t*>(samples);
    if constexpr (kBytes == 2) {
      std::uint8_t* out = swapped.data() + std::size_t(y % 2) * rowBytes;
      for (std::size_t i = 0; i < rowSamples; ++i) {
        out[2 * i] = std::uint8_t(samples[i] >> 8);
        out[2 * i + 1] = std::uint8_t(samples[i] & 0xFFu);
      }
      row = out;
    }
    std::uint8_t* out = filtered.data() + std::size_t(y) * (rowBytes + 1);
    *out++ = 4;  // filter type: Paeth
    for (std::size_t i = 0; i < rowBytes; ++i) {
      const int a = i >= pixelBytes ? row[i - pixelBytes] : 0;
      const int b = previous ? previous[i] : 0;
      const int c = previous && i >= pixelBytes ? previous[i - pixelBytes] : 0;
      out[i] = std::uint8_t(row[i] - paeth(a, b, c));
    }
    previous = row;
  }

  const std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> compressor(
      libdeflate_alloc_compressor(1), &libdeflate_free_compressor);
  if (!compressor) fail(source, ": PNG encoding failed (out of memory)");
  static constexpr std::uint8_t kSignature[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  static constexpr std::uint8_t kColorType[] = {0, 0, 4, 2, 6};  // by channels: grey, grey+alpha, RGB, RGBA
  constexpr std::size_t kIhdrAt = sizeof kSignature, kIdatAt = kIhdrAt + 12 + 13;
  const std::size_t bound = libdeflate_zlib_compress_bound(compressor.get(), filtered.size());
  std::vector<std::uint8_t> png(kIdatAt + 12 + bound + 12);
  std::memcpy(png.data(), kSignature, sizeof kSignature);
  // A chunk: length, type, data, CRC-32 of type and data.
  const auto finishChunk = [&](std::size_t at, const char* type, std::size_t length) {
    putBigEndian32(png.data() + at, std::uint32_t(length));
    std::memcpy(png.data() + at + 4, type, 4);
    putBigEndian32(png.data() + at + 8 + length, libdeflate_crc32(0, png.data() + at + 4, length + 4));
    return at + 12 + length;
  };
  putBigEndian32(png.data() + kIhdrAt + 8, std::uint32_t(image.width));
  putBigEndian32(png.data() + kIhdrAt + 12, std::uint32_t(image.height));
  const std::uint8_t header[] = {std::uint8_t(8 * kBytes), kColorType[image.channels], 0, 0, 0};
  std::memcpy(png.data() + kIhdrAt + 16, header, sizeof header);
  finishChunk(kIhdrAt, "IHDR", 13);
  const std::size_t compressed =
      libdeflate_zlib_compress(compressor.get(), filtered.data(), filtered.size(), png.data() + kIdatAt + 8, bound);
  if (compressed == 0) fail(source, ": PNG encoding failed (compressed data over its bound)");
  const std::size_t end = finishChunk(finishChunk(kIdatAt, "IDAT", compressed), "IEND", 0);
  png.resize(end);
  return png;
}

}  // namespace

namespace {

std::string readFile(const std::filesystem::path& path) {
  return readInputFile(path, "image", budget::kImageFileBytes);
}

std::span<const std::uint8_t> asBytes(const std::string& bytes) {
  return {reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()};
}

std::uint32_t bigEndian32(const std::uint8_t* p) {
  return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | std::uint32_t(p[3]);
}

// The size budget, checked on the header before any pixel memory exists.
void checkImageSize(long long w, long long h, const std::string& source) {
  if (w <= 0 || h <= 0) fail(source, ": image has no pixels (", w, "x", h, ")");
  if (w > budget::kImageSide_px || h > budget::kImageSide_px || w * h > budget::kImagePixels) {
    fail(source, ": ", w, "x", h, " pixels is over the limit of ", budget::kImageSide_px, " per side and ",
         budget::kImagePixels, " pixels (docs/RELIABILITY.md)");
  }
}

// stb trusts PNG chunk lengths and grows its buffer to match before reading, so a corrupt
// 100-byte file could make it reserve gigabytes. Check the chunk structure first.
void checkPngChunks(std::span<const std::uint8_t> bytes, const std::string& source) {
  static constexpr std::uint8_t kSignature[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kSignature, 8) != 0) return;
  std::size_t at = 8;
  while (at + 12 <= bytes.size()) {
    const std::uint32_t length = bigEndian32(bytes.data() + at);
    const std::string type(reinterpret_cast<const char*>(bytes.data() + at + 4), 4);
    if (type == "IHDR" && length >= 8 && at + 16 <= bytes.size() - 8) {
      checkImageSize(bigEndian32(bytes.data() + at + 8), bigEndian32(bytes.data() + at + 12), source);
    }
    if (length > bytes.size() - at - 12) {
      fail(source, ": cannot decode (PNG chunk '", type, "' claims ", length, " bytes but only ",
           bytes.size() - at - 12, " remain: truncated or corrupt file)");
    }
    if (type == "IEND") return;
    at += 12 + std::size_t(length);
  }
  fail(source, ": cannot decode (PNG ends without an IEND chunk: truncated file)");
}

// Decodes 8-bit (Sample = uint8) or 16-bit samples with stb after the structural checks.
template <class Sample>
Image<Sample> decode(std::span<const std::uint8_t> bytes, const std::string& source, int channels) {
  checkChannels(channels, source);
  checkPngChunks(bytes, source);
  if (bytes.size() > std::size_t(std::numeric_limits<int>::max())) fail(source, ": file too large");
  int w = 0, h = 0, fileChannels = 0;
  if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &w, &h, &fileChannels)) {
    fail(source, ": cannot decode (", stbi_failure_reason(), ")");
  }
  checkImageSize(w, h, source);
  std::unique_ptr<Sample, StbFree> data;
  if constexpr (sizeof(Sample) == 1) {
    data.reset(stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &fileChannels, channels));
  } else {
    data.reset(stbi_load_16_from_memory(bytes.data(), int(bytes.size()), &w, &h, &fileChannels, channels));
  }
  if (!data) fail(source, ": cannot decode (", stbi_failure_reason(), ")");
  Image<Sample> image(w, h, channels);
  std::memcpy(image.pixels.data(), data.get(), image.pixels.size() * sizeof(Sample));
  return image;
}

}  // namespace

Image8 loadImage8(const std::filesystem::path& path, int channels) {
  return decode<std::uint8_t>(asBytes(readFile(path)), describe(path), channels);
}

Image8 loadImage8(std::span<const std::uint8_t> bytes, const std::string& sourceName, int channels) {
  return decode<std::uint8_t>(bytes, sourceName, channels);
}

Image16 loadImage16(const std::filesystem::path& path, int channels) {
  return decode<std::uint16_t>(asBytes(readFile(path)), describe(path), channels);
}

Image16 loadImage16(std::span<const std::uint8_t> bytes, const std::string& sourceName, int channels) {
  return decode<std::uint16_t>(bytes, sourceName, channels);
}

bool is16BitImage(std::span<const std::uint8_t> bytes) {
  return bytes.size() <= std::size_t(std::numeric_limits<int>::max()) &&
         stbi_is_16_bit_from_memory(bytes.data(), int(bytes.size())) != 0;
}

ImageF loadChannelAsFloat(const std::filesystem::path& path, int channel) {
  if (channel < 0 || channel > 3) fail(describe(path), ": channel ", channel, " out of range 0..3");
  const bool grey = [&] {
    int w = 0, h = 0, c = 0;
    if (!stbi_info(path.c_str(), &w, &h, &c)) return false;
    return c <= 2;
  }();
  const Image16 source = loadImage16(path, grey ? 1 : 4);
  const int picked = grey ? 0 : channel;
  ImageF out(source.width, source.height, 1);
  for (std::size_t i = 0; i < out.pixels.size(); ++i) {
    out.pixels[i] = float(source.pixels[i * source.channels + picked]) / 65535.0f;
  }
  return out;
}

void savePng(const std::filesystem::path& path, const Image8& image) {
  const std::vector<std::uint8_t> png = encodePngFile(image, describe(path));
  writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

void savePng16(const std::filesystem::path& path, const Image16& image) {
  const std::vector<std::uint8_t> png = encodePngFile(image, describe(path));
  writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

std::vector<std::uint8_t> encodePng(const Image8& image) { return encodePngFile(image, "PNG encoder"); }

std::vector<std::uint8_t> encodePng16(const Image16& image) { return encodePngFile(image, "PNG encoder"); }

}  // namespace vt
