// Replayable recordings (`vtouching replay FILE`): files users keep and share. The whole replay
// runs, its pipeline included (the recorded times drive the haptic loop), against the built-in
// scene loaded once, whatever scene the input names.
#include <cstdint>
#include <sstream>
#include <string>

#include "modes/recording.hpp"
#include "vt/core/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const vt::app::LoadedScene scene = vt::app::loadScene({.builtin = true});
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    (void)vt::app::replayRecording(in, "fuzz", [](const vt::app::SceneOptions&) { return scene; });
  } catch (const vt::Error&) {
  }
  return 0;
}
