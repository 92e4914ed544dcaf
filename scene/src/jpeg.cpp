#include "vt/scene/jpeg.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include "vt/core/error.hpp"

namespace vt {

std::vector<std::uint8_t> encodeJpeg(const Image8& image, int quality) {
  if (image.channels < 1 || image.channels > 4) fail("encodeJpeg: ", image.channels, " channels (expected 1..4)");
  if (image.width <= 0 || image.height <= 0 || image.pixels.size() != std::size_t(image.width) * image.height * image.channels)
    fail("encodeJpeg: empty or inconsistent image (", image.width, "x", image.height, ")");
  if (quality < 1 || quality > 100) fail("encodeJpeg: quality ", quality, " not in 1..100");
  std::vector<std::uint8_t> out;
  out.reserve(std::size_t(image.width) * image.height / 8);
  const auto append = [](void* context, void* data, int size) {
    auto* bytes = static_cast<std::uint8_t*>(data);
    static_cast<std::vector<std::uint8_t>*>(context)->insert(static_cast<std::vector<std::uint8_t>*>(context)->end(),
                                                             bytes, bytes + size);
  };
  if (!stbi_write_jpg_to_func(append, &out, image.width, image.height, image.channels, image.pixels.data(), quality))
    fail("encodeJpeg: stb could not encode a ", image.width, "x", image.height, " image");
  return out;
}

Image8 decodeJpeg(std::span<const std::uint8_t> bytes, const std::string& source) {
  // Checked here, before stb sizes its buffers from the header.
  if (bytes.size() > kMaxJpegBytes) fail(source, ": JPEG of ", bytes.size(), " bytes exceeds the ", kMaxJpegBytes, "-byte limit");
  if (bytes.size() < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8 || bytes[2] != 0xFF)
    fail(source, ": not a JPEG (no start-of-image marker)");
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels))
    fail(source, ": cannot decode JPEG header (", stbi_failure_reason(), ")");
  if (w <= 0 || h <= 0 || static_cast<long long>(w) * h > kMaxJpegPixels)
    fail(source, ": JPEG size ", w, "x", h, " outside 1..", kMaxJpegPixels, " pixels");
  return loadImage8(bytes, source, 4);
}

}  // namespace vt
