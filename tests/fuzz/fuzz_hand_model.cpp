// Hand models (--hand-model) from untrusted glTF files: skins, joint names, JOINTS_0/WEIGHTS_0,
// inverse bind matrices, extras.
#include <cstdint>
#include <string>

#include "vt/core/error.hpp"
#include "vt/scene/hand_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    // Data-URI buffers only: no file access from the base directory.
    const vt::HandMesh hand =
        vt::loadHandModel(bytes, size > 4 && bytes.compare(0, 4, "glTF") == 0, "fuzz input", "/nonexistent");
    vt::validateHandMesh(hand, "fuzz input");  // what a loaded model promises the renderer
  } catch (const vt::Error&) {
  }
  return 0;
}
