// Image decoding of untrusted files (textures, photos, vibration maps). Every image that decodes
// is encoded again as `export` and `acquire` write PNGs (8-bit, and 16-bit where the input is) and
// decoded once more: the pixels must come back exactly (PNG is lossless; anything else aborts).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>

#include "vt/core/error.hpp"
#include "vt/scene/image.hpp"

namespace {

// Larger images are decoded but not encoded again: the encoder's code is the same at any size,
// and encoding every decoded image slowed the decoder's fuzzing from about 28 000 inputs a second
// (ASan) to 53, with this limit at 256 x 256 pixels to 1 100, at 64 x 64 to 5 900.
constexpr std::size_t kLargestReencoded_px = 64 * 64;

template <class Image, class Load>
void checkReencoded(const Image& image, const std::vector<std::uint8_t>& png, Load&& load) {
  try {
    if (load(png).pixels == image.pixels) return;
    std::fprintf(stderr, "a %dx%d image encoded again decodes to other pixels\n", image.width, image.height);
  } catch (const vt::Error& e) {
    std::fprintf(stderr, "a %dx%d image encoded again does not decode: %s\n", image.width, image.height, e.what());
  }
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span bytes(data, size);
  try {
    const vt::Image8 image = vt::loadImage8(bytes, "fuzz input", 4);
    if (image.pixels.size() != std::size_t(image.width) * image.height * 4) __builtin_trap();
    if (std::size_t(image.width) * image.height > kLargestReencoded_px) return 0;
    checkReencoded(image, vt::encodePng(image), [](const std::vector<std::uint8_t>& png) { return vt::loadImage8(png, "encoded", 4); });
    if (vt::is16BitImage(bytes)) {
      const vt::Image16 deep = vt::loadImage16(bytes, "fuzz input", 1);
      checkReencoded(deep, vt::encodePng16(deep), [](const std::vector<std::uint8_t>& png) { return vt::loadImage16(png, "encoded", 1); });
    }
  } catch (const vt::Error&) {
    // Rejected with a message: the expected outcome for bad input.
  }
  return 0;
}
