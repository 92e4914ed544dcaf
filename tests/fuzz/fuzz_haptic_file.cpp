// Haptic files from other tools: HJIF, AHAP and Meta .haptic (the same bytes through each reader).
#include <cstdint>
#include <string>

#include "vt/core/error.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace files = vt::haptics::files;
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (int format = 0; format < 3; ++format) {
    try {
      const files::HapticClip clip = format == 0 ? files::readHjif(text, "fuzz")
                                     : format == 1 ? files::readAhap(text, "fuzz", vt::haptics::ActuatorId::Index)
                                                   : files::readMetaHaptic(text, "fuzz", vt::haptics::ActuatorId::Index);
      (void)files::envelopeAt(clip.channels.front().envelope, clip.duration_s * 0.5);
    } catch (const vt::Error&) {
    }
  }
  return 0;
}
