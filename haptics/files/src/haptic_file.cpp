#include "vt/haptics/files/haptic_formats.hpp"

#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/core/output_file.hpp"

namespace vt::haptics::files {

std::vector<std::filesystem::path> saveHapticFile(const HapticClip& clip, const std::filesystem::path& path, bool replace) {
  const std::string ext = path.extension().string();
  if (clip.channels.empty()) fail("haptic file '", path.string(), "': the clip has no channel");
  std::vector<FileContent> files;
  if (ext == ".hjif") {
    files.push_back({path, writeHjif(clip) + '\n'});
  } else if (ext == ".ahap" || ext == ".haptic") {
    for (std::size_t c = 0; c < clip.channels.size(); ++c) {
      const std::filesystem::path file =
          clip.channels.size() == 1 ? path
                                    : path.parent_path() / str(path.stem().string(), "-", actuatorName(clip.channels[c].actuator), ext);
      files.push_back({file, (ext == ".ahap" ? writeAhap(clip, c) : writeMetaHaptic(clip, c)) + '\n'});
    }
  } else {
    fail("haptic file '", path.string(), "': expected .hjif, .ahap or .haptic");
  }
  writeFiles(files, replace);
  std::vector<std::filesystem::path> written;
  for (const FileContent& file : files) written.push_back(file.path);
  return written;
}

HapticClip loadHapticFile(const std::filesystem::path& path, ActuatorId actuator) {
  const std::string ext = path.extension().string();
  const std::string source = "haptic file '" + path.string() + "'";
  if (ext != ".hjif" && ext != ".ahap" && ext != ".haptic") fail(source, ": expected .hjif, .ahap or .haptic");
  const std::string text = readInputFile(path, "haptic file", budget::kHapticFileBytes);
  if (ext == ".hjif") return readHjif(text, source);
  const ActuatorId target = actuatorFromFileName(path, actuator);
  return ext == ".ahap" ? readAhap(text, source, target) : readMetaHaptic(text, source, target);
}

}  // namespace vt::haptics::files
