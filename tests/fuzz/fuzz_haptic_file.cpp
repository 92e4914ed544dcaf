// Haptic files from other tools and our own recordings read back: HJIF, AHAP, Meta .haptic, WAV
// and the actuator CSV (the same bytes through each reader).
#include <cstdint>
#include <string>

#include "vt/core/error.hpp"
#include "vt/haptics/files/haptic_clip.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace files = vt::haptics::files;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto read = [&](int format) {
    switch (format) {
      case 0: return files::readHjif(text, "fuzz");
      case 1: return files::readAhap(text, "fuzz", vt::haptics::ActuatorId::Index);
      case 2: return files::readMetaHaptic(text, "fuzz", vt::haptics::ActuatorId::Index);
      case 3: return files::readWav(text, "fuzz");
      default: return files::readActuatorCsv(text, "fuzz");
    }
  };
  for (int format = 0; format < 5; ++format) {
    try {
      const files::HapticClip clip = read(format);
      for (const files::ClipChannel& channel : clip.channels) {
        if (!channel.envelope.empty()) (void)files::envelopeAt(channel.envelope, clip.duration_s * 0.5);
      }
    } catch (const vt::Error&) {
    }
  }
  return 0;
}
