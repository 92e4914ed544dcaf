// `vtouching convert IN --out OUT`: a haptic clip from one of HJIF, AHAP, Meta .haptic and WAV to
// another, saying what the target cannot carry and splitting what one file cannot hold
// (docs/haptic-files.md, "Converting").
#include <cstdio>

#include "cli.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

namespace files = vt::haptics::files;

VT_COMMAND(convert) {
  const auto out = args.value("out");
  const std::string actuator = args.valueOr("actuator", "index");
  const bool force = args.flag("force");
  const auto positional = args.positionals();
  args.finish();
  if (positional.size() != 1) vt::fail("convert: expected one input file (.hjif, .ahap, .haptic or .wav)");
  if (!out) vt::fail("convert: --out FILE is required (.hjif, .ahap, .haptic or .wav)");
  files::hapticFormat(positional[0]);  // the input's extension first: its error names the input
  const files::HapticFormat target = files::hapticFormat(*out);
  const auto clip = files::loadHapticFile(positional[0], files::parseActuator(actuator, "convert: --actuator"));
  const auto written = files::saveHapticFile(clip, *out, force);
  for (const auto& file : written) std::printf("wrote %s\n", file.c_str());
  if (const std::size_t parts = files::fileParts(clip, target).size(); parts > 1)
    std::printf("split into %zu parts: a file holds at most %.0f s and what play reads (%llu MiB)\n", parts,
                files::kMaxClip_s, static_cast<unsigned long long>(vt::budget::kHapticFileBytes >> 20));
  for (const std::string& loss : files::conversionLosses(clip, target)) std::printf("lost: %s\n", loss.c_str());
  return 0;
}
