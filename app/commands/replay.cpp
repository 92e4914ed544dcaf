// `vtouching replay FILE`: re-runs a recording's poses through a fresh haptic loop and checks
// that every actuator frame comes out the same (docs/app.md).
#include <cstdio>

#include "cli.hpp"
#include "modes/recording.hpp"
#include "vt/core/error.hpp"

VT_COMMAND(replay, "replay FILE [--out FRAMES.csv]",
           "replay a --record file deterministically; exit 0 when the actuator output matches") {
  const auto out = args.valueOr("out", "");
  const auto files = args.positionals();
  args.finish();
  if (files.size() != 1) vt::fail("replay: expected one recording file");
  const vt::app::ReplayResult r = vt::app::replayRecording(files[0], out);
  std::printf("replayed %llu actuator frames (%llu poses, %llu contact records): %llu differ, max difference %.3g\n",
              static_cast<unsigned long long>(r.frames), static_cast<unsigned long long>(r.poses),
              static_cast<unsigned long long>(r.contacts), static_cast<unsigned long long>(r.mismatches),
              r.maxDifference);
  if (r.frames == 0) vt::fail("replay: ", files[0], ": the recording holds no actuator frames");
  return r.mismatches == 0 ? 0 : 4;
}
