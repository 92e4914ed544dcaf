// glTF scenes from untrusted files: JSON structure, accessors, indices, tactile extras.
#include <cstdint>
#include <string>

#include "vt/core/error.hpp"
#include "vt/scene/loaders.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    // Data-URI buffers only: no file access from the base directory.
    const vt::Scene scene = vt::loadGltfScene(bytes, size > 4 && bytes.compare(0, 4, "glTF") == 0, "fuzz input",
                                              "/nonexistent");
    scene.validate();
  } catch (const vt::Error&) {
  }
  return 0;
}
