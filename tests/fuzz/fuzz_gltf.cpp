// glTF scenes from untrusted files: JSON structure, accessors, indices, tactile extras. Every scene
// that loads is then exported as `vtouching export` does (.glb) and loaded again: the export may
// refuse with vt::Error, but a file it writes must load (anything else aborts, a finding).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "vt/core/error.hpp"
#include "vt/scene/gltf_writer.hpp"
#include "vt/scene/loaders.hpp"

namespace {

// This process's folder for the exported file, removed when it exits.
struct ExportFolder {
  std::filesystem::path path = std::filesystem::temp_directory_path() / ("vt-fuzz-gltf-" + std::to_string(::getpid()));
  ExportFolder() { std::filesystem::create_directories(path); }
  ~ExportFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

void exportAndReload(const vt::Scene& scene) {
  static const ExportFolder folder;
  const std::filesystem::path file = folder.path / "export.glb";
  try {
    vt::saveGltfScene(scene, file, true);
  } catch (const vt::Error&) {
    return;  // refused, with a clear error: allowed
  }
  try {
    vt::loadGltfScene(file).validate();
  } catch (const vt::Error& e) {
    std::fprintf(stderr, "a scene the export wrote does not load back: %s\n", e.what());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  vt::Scene scene;
  try {
    // Data-URI buffers only: no file access from the base directory.
    scene = vt::loadGltfScene(bytes, size > 4 && bytes.compare(0, 4, "glTF") == 0, "fuzz input", "/nonexistent");
    scene.validate();
  } catch (const vt::Error&) {
    return 0;
  }
  exportAndReload(scene);
  return 0;
}
