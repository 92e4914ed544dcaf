#pragma once
// The motions a person makes on the grating plate (x along the grating, across it z), and the
// scripts that play them: a cursor script for the desktop (the plate points projected into the
// window through the grating scene's camera) and an xrsim hand-tracking script (stage space).
#include <filesystem>
#include <string>
#include <vector>

namespace vt::live {

/// One keyframe: where the index fingertip is on the plate and whether it presses; minimum-jerk
/// moves between keyframes, the press state holds from its keyframe on.
struct MotionKey {
  double t_s = 0.0;
  float x_m = 0.0f, z_m = 0.0f;
  bool press = false;
};

/// Touch down, a reach and a stop, a reversal, a slow slide, a lift-off and a fast re-touch:
/// peak speeds 0.02 to 0.5 m/s, 7.5 s a round; `rounds` of them, 0.5 s apart (3: 23.5 s).
std::vector<MotionKey> personMotions(int rounds);

/// A --cursor-script file for a window of `size` ("WxH") showing the grating scene.
void writeCursorScript(const std::filesystem::path& file, const std::vector<MotionKey>& keys, const std::string& size);
/// An xrsim script: the right hand tracked, resting in the air for `rest_s`, then the motions
/// (sampled every 4 ms along the minimum-jerk moves) around the table at its fixed stage place.
void writeXrsimScript(const std::filesystem::path& file, const std::vector<MotionKey>& keys, double rest_s);

}  // namespace vt::live
