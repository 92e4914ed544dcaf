#include "vt/scene/image.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <array>
#include <cstring>
#include <limits>
#include <memory>
#include <string>

#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/core/output_file.hpp"

// Exported by Debian's libstb (stb_image_write's deflate), declared here because
// stb_image_write.h only declares it inside its implementation section.
extern "C" unsigned char* stbi_zlib_compress(unsigned char* data, int data_len, int* out_len, int quality);
extern "C" unsigned char* stbi_write_png_to_mem(const unsigned char* pixels, int stride_bytes, int x, int y, int n,
                                              int* out_len);

namespace vt {
namespace {

struct StbFree {
  void operator()(void* p) const noexcept { stbi_image_free(p); }
};

void checkChannels(int channels, const std::string& source) {
  if (channels < 1 || channels > 4) fail(source, ": requested ", channels, " channels (expected 1..4)");
}

std::string describe(const std::filesystem::path& path) { return "image '" + path.string() + "'"; }

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0) {
  static const auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) crc = table[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

void putBigEndian32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(std::uint8_t(v >> shift));
}

void appendChunk(std::vector<std::uint8_t>& png, const char type[4], const std::uint8_t* data, std::size_t size) {
  putBigEndian32(png, std::uint32_t(size));
  const std::size_t typeStart = png.size();
  png.insert(png.end(), type, type + 4);
  png.insert(png.end(), data, data + size);
  putBigEndian32(png, crc32(png.data() + typeStart, size + 4));
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
  checkChannels(image.channels, describe(path));
  if (image.empty()) fail(describe(path), ": refusing to write an empty image");
  // stb ignores fwrite errors, so it only encodes; OutputFile checks every write and the close.
  std::string png;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
  };
  if (!stbi_write_png_to_func(append, &png, image.width, image.height, image.channels, image.pixels.data(),
                              image.width * image.channels)) {
    fail(describe(path), ": PNG encoding failed");
  }
  writeFileAtomically(path, png);
}

std::vector<std::uint8_t> encodePng(const Image8& image) {
  checkChannels(image.channels, "PNG encoder");
  if (image.empty()) fail("PNG encoder: refusing to encode an empty image");
  int size = 0;
  std::unique_ptr<unsigned char, decltype(&std::free)> bytes(
      stbi_write_png_to_mem(image.pixels.data(), image.width * image.channels, image.width, image.height,
                            image.channels, &size),
      &std::free);
  if (!bytes) fail("PNG encoder: compression failed");
  return {bytes.get(), bytes.get() + size};
}

std::vector<std::uint8_t> encodePng16(const Image16& image) {
  checkChannels(image.channels, "PNG encoder");
  if (image.empty()) fail("PNG encoder: refusing to encode an empty image");
  // stb_image_write has no 16-bit PNG; build the chunks around stb's deflate ourselves.
  static constexpr std::uint8_t kColorType[] = {0, 0, 4, 2, 6};  // grey, grey+alpha, RGB, RGBA
  const std::size_t rowBytes = std::size_t(image.width) * image.channels * 2;
  std::vector<std::uint8_t> raw;
  raw.reserve((rowBytes + 1) * image.height);
  for (int y = 0; y < image.height; ++y) {
    raw.push_back(0);  // filter: none
    for (int i = 0; i < image.width * image.channels; ++i) {
      const std::uint16_t v = image.pixels[std::size_t(y) * image.width * image.channels + i];
      raw.push_back(std::uint8_t(v >> 8));
      raw.push_back(std::uint8_t(v & 0xFFu));
    }
  }
  int compressedSize = 0;
  std::unique_ptr<unsigned char, decltype(&std::free)> compressed(
      stbi_zlib_compress(raw.data(), int(raw.size()), &compressedSize, 6), &std::free);
  if (!compressed) fail("PNG encoder: compression failed");

  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> header;
  putBigEndian32(header, std::uint32_t(image.width));
  putBigEndian32(header, std::uint32_t(image.height));
  header.insert(header.end(), {16, kColorType[image.channels], 0, 0, 0});
  appendChunk(png, "IHDR", header.data(), header.size());
  appendChunk(png, "IDAT", compressed.get(), std::size_t(compressedSize));
  appendChunk(png, "IEND", nullptr, 0);
  return png;
}

void savePng16(const std::filesystem::path& path, const Image16& image) {
  checkChannels(image.channels, describe(path));
  if (image.empty()) fail(describe(path), ": refusing to write an empty image");
  const std::vector<std::uint8_t> png = encodePng16(image);
  writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

}  // namespace vt
