// Haptic files from other tools and our own recordings read back: HJIF, AHAP, Meta .haptic, WAV
// and the actuator CSV (the same bytes through each reader). Every clip a reader accepts is then
// written in each format, as `vtouching convert` does, and read back: a writer may refuse a clip
// with vt::Error, but a file it writes must read back (anything else aborts, a finding).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "vt/core/error.hpp"
#include "vt/haptics/files/haptic_clip.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

namespace {

namespace files = vt::haptics::files;

// Of a longer clip only its first part this long is written (cut by clipPart, as convert cuts its
// parts): a WAV of ten actuators takes 160 kB a second, which would slow every input without
// reaching more code.
constexpr double kLongestWritten_s = 2.0;

// Writes `clip` with `write` (which may refuse) and reads the text back with `read`.
template <class Write, class Read>
void roundTrip(const char* format, Write&& write, Read&& read) {
  std::string text;
  try {
    text = write();
  } catch (const vt::Error&) {
    return;  // refused, with a clear error: allowed
  }
  try {
    (void)read(text);
  } catch (const vt::Error& e) {
    std::fprintf(stderr, "a %s file the writer made does not read back: %s\n", format, e.what());
    std::abort();
  }
}

void writeEveryFormat(const files::HapticClip& whole) {
  if (whole.channels.empty()) return;
  for (const files::HapticFormat format : {files::HapticFormat::Hjif, files::HapticFormat::Ahap, files::HapticFormat::Meta,
                                           files::HapticFormat::Wav}) {
    try {
      (void)files::fileParts(whole, format);  // how convert would split it
    } catch (const vt::Error&) {
    }
  }
  const files::HapticClip clip =
      whole.duration_s <= kLongestWritten_s ? whole : files::clipPart(whole, 0.0, kLongestWritten_s);
  roundTrip("HJIF", [&] { return files::writeHjif(clip); }, [](const std::string& t) { return files::readHjif(t, "written"); });
  roundTrip("WAV", [&] { return files::writeWav(clip); }, [](const std::string& t) { return files::readWav(t, "written"); });
  for (std::size_t c = 0; c < clip.channels.size(); ++c) {
    const vt::haptics::ActuatorId actuator = clip.channels[c].actuator;
    roundTrip("AHAP", [&] { return files::writeAhap(clip, c); },
              [&](const std::string& t) { return files::readAhap(t, "written", actuator); });
    roundTrip(".haptic", [&] { return files::writeMetaHaptic(clip, c); },
              [&](const std::string& t) { return files::readMetaHaptic(t, "written", actuator); });
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
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
    files::HapticClip clip;
    try {
      clip = read(format);
    } catch (const vt::Error&) {
      continue;
    }
    for (const files::ClipChannel& channel : clip.channels) {
      if (!channel.envelope.empty()) (void)files::envelopeAt(channel.envelope, clip.duration_s * 0.5);
    }
    writeEveryFormat(clip);
  }
  return 0;
}
