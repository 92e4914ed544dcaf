// `vtouching play FILE`: a haptic file (HJIF, AHAP, Meta .haptic, WAV) played on the glove.
#include <chrono>
#include <cstdio>
#include <thread>

#include "cli.hpp"
#include "vt/core/error.hpp"
#include "vt/core/stop.hpp"
#include "vt/haptics/devices/glove_setup.hpp"
#include "vt/haptics/devices/recorder.hpp"
#include "vt/haptics/files/clip_player.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

namespace {

namespace files = vt::haptics::files;

// Plays the clip in real time on the glove `spec` (sim, hid, ...), or as fast as possible with no
// glove ("none"), handing every frame to `recorder` when there is one. Small on purpose: the
// session composition root will own the glove and the sinks.
void playClip(const files::ClipPlayer& player, const std::string& spec, vt::haptics::ActuatorRecorder* recorder) {
  std::unique_ptr<vt::haptics::glove::GloveSetup> glove;
  if (spec != "none") {
    glove = vt::haptics::glove::GloveSetup::create(spec);
    // A clip played to no device is lost: unlike the live modes, play does not wait for a glove
    // to be plugged in.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
    while (!glove->driver().status().connected && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (const auto status = glove->driver().status(); !status.connected)
      vt::fail("play: no glove found for --glove ", spec, status.lastError.empty() ? "" : " (" + status.lastError + ")");
  }
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t tick = 0; tick <= player.tickCount(); ++tick) {
    const vt::haptics::ActuatorFrame frame = player.frame(tick);  // the last one is silent
    if (vt::stopRequested()) {
      // Ctrl-C: the glove's failsafe already holds it silent; the recording ends on silence too.
      if (recorder) recorder->record(vt::haptics::ActuatorFrame::silent(frame.actuatorCount, frame.t_ns));
      std::printf("stopped (Ctrl-C) at %.3f s\n", double(frame.t_ns) * 1e-9);
      return;
    }
    if (recorder) recorder->record(frame);
    if (!glove) continue;
    std::this_thread::sleep_until(start + std::chrono::nanoseconds(frame.t_ns));
    glove->driver().submit(frame);
  }
}

}  // namespace

VT_COMMAND(play) {
  const std::string glove = args.valueOr("glove", "sim");
  const std::string actuator = args.valueOr("actuator", "index");
  const std::string wav = args.valueOr("record-wav", "");
  const std::string csv = args.valueOr("record-csv", "");
  const auto positional = args.positionals();
  args.finish();
  if (positional.size() != 1) vt::fail("play: expected one FILE (.hjif, .ahap, .haptic or .wav)");
  const auto clip = files::loadHapticFile(positional[0], files::parseActuator(actuator, "play: --actuator"));
  const files::ClipPlayer player(clip);
  std::unique_ptr<vt::haptics::ActuatorRecorder> recorder;
  if (!wav.empty() || !csv.empty()) recorder = std::make_unique<vt::haptics::ActuatorRecorder>(csv, wav);
  std::printf("playing %s: %zu channel(s), %.3f s on glove %s\n", positional[0].c_str(), clip.channels.size(),
              clip.duration_s, glove.c_str());
  std::fflush(stdout);  // a long clip: whoever reads the log sees it start
  playClip(player, glove, recorder.get());
  if (recorder) {
    recorder->finish();
    if (!wav.empty())
      std::printf("recorded %llu samples per channel at %u Hz into %s\n",
                  static_cast<unsigned long long>(recorder->wavSamples()), recorder->sampleRate_hz(), wav.c_str());
    if (!csv.empty()) std::printf("recorded the actuator frames into %s\n", csv.c_str());
  }
  return 0;
}
