// Trajectory files (CSV and JSON) from users' experiment scripts.
#include <cstdint>
#include <string>

#include "vt/core/error.hpp"
#include "vt/scene/trajectory.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (bool json : {false, true}) {
    try {
      const vt::Trajectory t = json ? vt::parseTrajectoryJson(text, "fuzz") : vt::parseTrajectoryCsv(text, "fuzz");
      (void)t.poseAt(t.keys.front().t_s + t.duration_s() * 0.5);
    } catch (const vt::Error&) {
    }
  }
  return 0;
}
