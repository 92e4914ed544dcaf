#include <fstream>

#include "vt/core/error.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

namespace vt::haptics::files {
namespace {

void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text << '\n';
  if (!out) fail("haptic file '", path.string(), "': cannot write (does the folder exist?)");
}

}  // namespace

std::vector<std::filesystem::path> saveHapticFile(const HapticClip& clip, const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (clip.channels.empty()) fail("haptic file '", path.string(), "': the clip has no channel");
  if (ext == ".hjif") {
    writeText(path, writeHjif(clip));
    return {path};
  }
  if (ext != ".ahap" && ext != ".haptic") fail("haptic file '", path.string(), "': expected .hjif, .ahap or .haptic");
  std::vector<std::filesystem::path> written;
  for (std::size_t c = 0; c < clip.channels.size(); ++c) {
    const std::filesystem::path file =
        clip.channels.size() == 1 ? path
                                  : path.parent_path() / str(path.stem().string(), "-", actuatorName(clip.channels[c].actuator), ext);
    writeText(file, ext == ".ahap" ? writeAhap(clip, c) : writeMetaHaptic(clip, c));
    written.push_back(file);
  }
  return written;
}

HapticClip loadHapticFile(const std::filesystem::path& path, ActuatorId actuator) {
  const std::string ext = path.extension().string();
  const std::string source = "haptic file '" + path.string() + "'";
  if (ext != ".hjif" && ext != ".ahap" && ext != ".haptic") fail(source, ": expected .hjif, .ahap or .haptic");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(source, ": cannot open");
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  if (ext == ".hjif") return readHjif(text, source);
  const ActuatorId target = actuatorFromFileName(path, actuator);
  return ext == ".ahap" ? readAhap(text, source, target) : readMetaHaptic(text, source, target);
}

}  // namespace vt::haptics::files
