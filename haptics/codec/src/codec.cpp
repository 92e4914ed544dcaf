#include "vt/haptics/codec/codec.hpp"

#include "codec_internal.hpp"
#include "vt/core/error.hpp"

namespace vt::haptics {

std::unique_ptr<TactileCodec> makeCodec(CodecId id, int quality) {
  if (quality < 0 || quality > 100) fail("codec quality ", quality, " is outside 0..100");
  switch (id) {
    case CodecId::RawFloat32: return codec::makeRawFloat32();
    case CodecId::Pcm16: return codec::makePcm16();
    case CodecId::Perceptual: return codec::makePerceptual(quality);
  }
  fail("unknown tactile codec id ", int(id));
}

bool isKnownCodec(std::uint8_t id) noexcept { return id >= 1 && id <= 3; }

std::string_view codecName(CodecId id) noexcept {
  switch (id) {
    case CodecId::RawFloat32: return "raw-f32";
    case CodecId::Pcm16: return "pcm16";
    case CodecId::Perceptual: return "perceptual";
  }
  return "unknown";
}

bool parseCodecName(std::string_view name, CodecId& out) noexcept {
  for (std::uint8_t id = 1; id <= 3; ++id) {
    if (codecName(CodecId(id)) == name) {
      out = CodecId(id);
      return true;
    }
  }
  return false;
}

}  // namespace vt::haptics
