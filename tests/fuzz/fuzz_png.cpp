// Image decoding of untrusted files (textures, photos, vibration maps).
#include <cstdint>
#include <span>

#include "vt/core/error.hpp"
#include "vt/scene/image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const vt::Image8 image = vt::loadImage8(std::span(data, size), "fuzz input", 4);
    if (image.pixels.size() != std::size_t(image.width) * image.height * 4) __builtin_trap();
  } catch (const vt::Error&) {
    // Rejected with a message: the expected outcome for bad input.
  }
  return 0;
}
