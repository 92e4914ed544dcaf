// The vtouching command line, declared once (see option_table.hpp). A new option is one entry
// here plus the line of code that reads it; `vtouching help --check` and tests/app/cli_*
// check that the two agree, and VT_UPDATE_GOLDENS=1 regenerates docs/app.md's tables.
#include "cli/option_table.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "vt/core/error.hpp"

namespace vt::cli {
namespace {

using K = ValueKind;

constexpr SectionSpec kSections[] = {
    {"scene", "Scene"},
    {"tactile", "Tactile model"},
    {"outputs", "Outputs and recordings"},
    {"view", "Window, headset and input"},
    {"offscreen", "Offscreen runs"},
    {"network", "Client and server"},
    {"acquire", "Acquisition"},
    {"tools", "Statistics, export, playback, devices"},
    {"meta", "Help and global options"},
};

constexpr CommandSpec kCommands[] = {
    {"acquire", "robot + accelerometer logs + photo -> pixel-aligned vibration map (or simulate a scan)",
     "SCAN_DIR --out DATASET_DIR [options]\n--synthetic KIND --out SCAN_DIR [options]",
     "scan --out dataset\n--synthetic pattern_board --out scan"},
    {"client", "tactile client: desktop, headset or headless (trajectory) input; the server renders the touch",
     "--connect ADDR:PORT [options]", "--connect 127.0.0.1:47800"},
    {"completion", "the bash completion script (source <(vtouching completion bash))", "bash", "bash"},
    {"convert", "a haptic file into another format: HJIF, AHAP, Meta .haptic, WAV (losses stated; long clips split)",
     "IN.hjif|.ahap|.haptic|.wav --out OUT.hjif|.ahap|.haptic|.wav [options]", "clip.hjif --out clip.ahap"},
    {"devices", "lists Avatar-style gloves (hidapi), audio outputs (ALSA), the OpenXR runtime and the Vulkan devices",
     "[options]", ""},
    {"export",
     "a dataset as glTF with MPEG_haptic_material, an actuator recording as a haptic file, or the generated hand as "
     "a glTF skin to edit for --hand-model",
     "DATASET_DIR --out SCENE.glb|.gltf [options]\nREC.csv [REC.wav] --out FILE.hjif|.ahap|.haptic [--force]\n"
     "--hand-template --out HAND.glb|.gltf [--force]",
     "dataset --out scene.glb\nrec.csv --out rec.hjif\n--hand-template --out hand.glb"},
    {"help", "these commands, or one command's options", "[COMMAND]\n--man\n--check", "run"},
    {"play", "play a haptic file on the glove (none: no device, as fast as possible)",
     "FILE.hjif|.ahap|.haptic|.wav [options]", "clip.hjif"},
    {"render", "render a scene offscreen to PNGs and print the frame time, or run a scripted hand path",
     "--out DIR [options]\n--trajectory FILE --out DIR [options]", "--out out\n--trajectory path.csv --out out"},
    {"replay", "replay a --record file deterministically; exit 0 when the actuator output matches",
     "FILE [--out DIR [options]]", "session.txt"},
    {"run", "desktop preview (the default command): touch the objects with a mouse-driven hand; --xr for a headset",
     "[options]", ""},
    {"serve", "tactile server: the haptic loop on the scene for one remote client (loopback by default)", "[options]",
     ""},
    {"stats", "Table-I statistics (V_scale, V_mean, V_std) per object: CSV (or --json) on stdout, or files in --out",
     "DATASET_DIR [options]", "dataset"},
};

// clang-format off
constexpr OptionSpec kOptions[] = {
    // Scene: where the objects come from (app/modes/scene_source.cpp).
    {"scene", "FILE.gltf", K::Path, "", "run client serve render export", "scene",
     "glTF 2.0 scene (.gltf or .glb), tactile maps in material extras or MPEG_haptic_material (docs/scene-format.md)"},
    {"dataset", "DIR", K::Path, "", "run client serve render export", "scene",
     "a folder in the published Pixel2Taxel layout (NAME/NAME.png + NAME/NAME_acc.png)"},
    {"builtin", "", K::Flag, "", "run client serve render export", "scene",
     "the procedural demo scene, ignoring the assets"},
    {"mm-per-pixel", "MM", K::Number, "0", "run client serve render export", "scene",
     "size of a photo pixel, 0..100 mm; 0: per object NAME_map.json, else estimated from the taxel rows, else 0.3"},
    {"intensity", "absolute|normalised", K::Choice, "absolute", "run client serve render export", "scene",
     "intensities comparable across objects (each map's normalisation from NAME_map.json), or the maps as published"},
    {"gains", "FILE", K::Path, "", "run client serve render export", "scene",
     "per-object gain table (name,gain CSV) for dataset scenes"},
    {"allow-outside-paths", "", K::Flag, "", "run client serve render export", "scene",
     "let a glTF's URIs name files outside its folder (docs/RELIABILITY.md)"},
    {"grating", "MM", K::Number, "0", "run client serve render export", "scene",
     "one 20 cm plate with a stripe grating of this period, 0..50 mm (a calibration target: felt frequency = speed / period)"},

    // Tactile model (app/modes/haptic_options.cpp).
    {"model", "paper|texture|taxel", K::Choice, "paper", "run serve render", "tactile",
     "the paper's intensity, a texture waveform, or measured per-taxel waveforms (docs/tactile-rendering.md)"},
    {"mapping", "five|vtouching", K::Choice, "five", "run serve render", "tactile",
     "contact points -> actuators: five fingertips, or the paper's glove (index, middle, ring)"},
    {"gain", "G", K::Number, "1", "run serve render", "tactile",
     "route gain 0..4, on top of each material's own gain"},
    {"rate", "HZ", K::Number, "1000", "run render", "tactile",
     "haptic tick rate, 250..4000 Hz (serve ticks once per received pose)"},
    {"pose-sampling", "latest|interpolate|predict", K::Choice, "predict", "run serve render", "tactile",
     "how each tick samples the hand from the pose history (docs/tactile-rendering.md, \"Time\")"},
    {"haptic-latency-ms", "MS", K::Number, "0", "run serve render", "tactile",
     "the output device's own delay, 0..200 ms: ticks sample the hand this much ahead"},
    {"haptic-pacing", "sleep|spin", K::Choice, "sleep", "run", "tactile",
     "the haptic thread sleeps between ticks, or spins on its core: steadier ticks for a whole core (docs/PERFORMANCE.md, \"Pacing the haptic thread\")"},

    // Outputs and recordings (TouchPipeline's sinks, app/modes/touch_pipeline.cpp).
    {"glove", "sim|hid|hid:SERIAL|hid:/dev/hidrawN|none", K::Choice, "sim", "run client play", "outputs",
     "the simulated glove, the first Avatar-style HID glove (or the one with that serial or node), or none"},
    {"glove", "sim|hid|hid:SERIAL|hid:/dev/hidrawN|none", K::Choice, "none", "render", "outputs",
     "a glove to drive during a --trajectory run"},
    {"output", "audio[:DEVICE]|osc://HOST:PORT[?blocks]", K::Choice, "", "run", "outputs",
     "each actuator's waveform on an ALSA device's channels, or levels (and blocks) as OSC (docs/outputs.md)", true},
    {"channels", "LIST", K::Text, "", "run", "outputs",
     "--output audio: the actuator on each device channel, e.g. thumb,index,-,middle (- = silent)"},
    {"record", "FILE", K::Path, "", "run client serve render", "outputs",
     "a recording of poses, contacts, actuator and displayed frames (replayable: vtouching replay; a client's is not)"},
    {"record-csv", "FILE", K::Path, "", "run client serve render play", "outputs",
     "the actuator frames as CSV (input of vtouching export)"},
    {"record-wav", "FILE", K::Path, "", "run client serve render play", "outputs",
     "the actuator waveforms as a multichannel WAV"},
    {"actuator", "NAME", K::Text, "index", "play convert", "outputs",
     "the actuator a one-channel file plays on (thumb, index, middle, ring, little, ...)"},

    // Window, headset and input (app/modes/desktop_mode.cpp, headset_mode.cpp, hand_view.cpp).
    {"xr", "", K::Flag, "", "run client", "view",
     "headset mode through OpenXR; without a runtime or headset, one line says why and the desktop opens"},
    {"xr-required", "", K::Flag, "", "run client", "view",
     "headset mode or exit code 5"},
    {"no-mirror", "", K::Flag, "", "run client", "view",
     "headset mode without the desktop mirror window"},
    {"size", "WxH", K::Size, "1280x720", "run client", "view",
     "window (or mirror window) size"},
    {"frames", "N", K::Integer, "0", "run client", "view",
     "quit after N frames and print the frame time (0: until closed)"},
    {"screenshot", "FILE", K::Path, "", "run client", "view",
     "the last frame (headset mode: mirror frame) as PNG; needs --frames N"},
    {"scripted-input", "", K::Flag, "", "run client", "view",
     "a fixed mouse path swept over the --frames N instead of the real mouse (tests)"},
    {"cursor-script", "FILE", K::Path, "", "run client", "view",
     "a scripted mouse: keyframes 't_s x y press' joined by minimum-jerk moves; the run ends with it (docs/app.md)"},
    {"max-fps", "F", K::Number, "0", "run client", "view",
     "at most F frames per second, 0..1000 (0: as fast as they render)"},
    {"no-frame-pacing", "", K::Flag, "", "run client", "view",
     "present each frame at once, not a planned time after its input (docs/tactile-rendering.md, \"Time\")"},
    {"fixed-table", "", K::Flag, "", "run client", "view",
     "headset mode: the table stays at its stage position (a lab's physical table), not placed before the head"},
    {"no-hud", "", K::Flag, "", "run client", "view",
     "hide the HUD panels"},
    {"glove-curls", "", K::Flag, "", "run client", "view",
     "the glove's flexion sensors curl the fingers (instead of keys 1-5)"},
    {"overlay", "", K::Flag, "", "run client render replay", "view",
     "the vibration maps drawn over the objects as a heat colour from the start"},
    {"hand", "mesh|skeleton", K::Choice, "mesh", "run client serve render replay", "view",
     "the skinned hand mesh, or (debug) a sphere per joint and a capsule per bone"},
    {"hand-model", "FILE.gltf", K::Path, "", "run client serve render replay", "view",
     "a glTF skin to draw instead of the generated hand (docs/renderer.md, \"Hand model\")"},
    {"validate", "", K::Flag, "", "run client render replay", "view",
     "the Vulkan validation layer on; exit 3 on any message"},
    {"demo-out", "DIR", K::Path, "vtouching-demo", "run", "view",
     "where the offscreen demo writes when there is no display"},

    // Offscreen runs (app/commands/render.cpp, app/modes/trajectory_run.cpp).
    {"trajectory", "FILE", K::Path, "", "render", "offscreen",
     "a scripted hand path (docs/trajectory-format.md): frames, traces and Fig. 5 figures"},
    {"out", "DIR", K::Path, "", "render replay", "offscreen",
     "the output folder (render needs it; replay re-renders into it)"},
    {"size", "WxH", K::Size, "", "render", "offscreen",
     "frame size (default 1280x720; 960x540 with --trajectory)"},
    {"size", "WxH", K::Size, "960x540", "replay", "offscreen",
     "frame size"},
    {"frames", "N", K::Integer, "10", "render", "offscreen",
     "views drawn to time the frame (without --trajectory), 1..100000"},
    {"fps", "F", K::Number, "30", "render replay", "offscreen",
     "frames per second of run time, 0..1000 (0: no frames, no GPU)"},
    {"every", "N", K::Integer, "1", "render replay", "offscreen",
     "keep every N-th frame"},
    {"video", "FILE.mp4", K::Path, "", "render replay", "offscreen",
     "the kept frames encoded into one video by ffmpeg instead of PNGs"},
    {"stereo", "", K::Flag, "", "render", "offscreen",
     "both eyes (left.png, right.png)"},
    {"texture", "FILE", K::Path, "", "render", "offscreen",
     "this image instead of the first plate's photo"},
    {"quiet", "", K::Flag, "", "render replay acquire stats", "offscreen",
     "print nothing but errors"},

    // Client and server (app/commands/serve.cpp, client.cpp, net_options.hpp).
    {"connect", "ADDR:PORT", K::Text, "", "client", "network",
     "the server's address and UDP port (required)"},
    {"bind", "ADDR:PORT", K::Text, "127.0.0.1:47800", "serve", "network",
     "the address and UDP port to serve on (0.0.0.0:PORT for a LAN)"},
    {"bind", "ADDR:PORT", K::Text, "", "client", "network",
     "the local address and port (default: any)"},
    {"key", "FILE", K::Path, "", "serve", "network",
     "the shared key (a new one is written to FILE when absent); required off loopback"},
    {"key", "FILE|HEX", K::Text, "", "client", "network",
     "the server's shared key: its file or its hex"},
    {"codecs", "LIST", K::Text, "perceptual,pcm16,raw-f32", "serve client", "network",
     "tactile codecs, most preferred first"},
    {"quality", "0..100", K::Integer, "50", "client", "network",
     "the perceptual codec's quality"},
    {"block-ms", "4|8|16|32|64|128", K::Choice, "", "serve", "network",
     "the only codec block length the server grants (default: what each client asks for)"},
    {"block-ms", "4|8|16|32|64|128", K::Choice, "4", "client", "network",
     "the codec block length to ask for (longer: fewer bits, more delay)"},
    {"blocks-per-datagram", "N", K::Integer, "1", "client", "network",
     "codec blocks sent in one datagram"},
    {"no-redundancy", "", K::Flag, "", "client", "network",
     "do not ask for each block again in the next datagram (one block period less delay, half the bytes; a lost datagram is concealed)"},
    {"timeout-ms", "MS", K::Integer, "1000", "serve", "network",
     "a session ends after this long without a pose, 1..65535 ms"},
    {"seconds", "N", K::Number, "0", "serve", "network",
     "stop after N seconds (0: at Ctrl-C)"},
    {"seconds", "N", K::Number, "", "client", "network",
     "stop after N seconds (default 5 headless, else at Ctrl-C or when closed)"},
    {"headless", "", K::Flag, "", "client", "network",
     "no window: the example trajectory drives the hand (also when there is no display)"},
    {"trajectory", "FILE", K::Path, "", "client", "network",
     "the headless hand path, looped (default: the example trajectory)"},
    {"json", "", K::Flag, "", "run client stats devices", "network",
     "the report as JSON (run, client: the end-of-session report with the consistency meter)"},
    {"video", "", K::Flag, "", "serve", "network",
     "render the scene and the hand from the scene's camera and stream it as JPEG to clients that ask"},
    {"video", "", K::Flag, "", "client", "network",
     "ask the server for its video (a window beside the desktop client's own view)"},
    {"video-fps", "N", K::Number, "15", "serve", "network",
     "video frames per second"},
    {"video-quality", "Q", K::Integer, "75", "serve", "network",
     "video JPEG quality"},
    {"video-out", "DIR", K::Path, "", "client", "network",
     "headless: the received video frames as DIR/frame_N.jpg (implies --video)"},
    {"loss", "P", K::Number, "0", "serve client", "network",
     "impair what this side receives: drop probability 0..1 (docs/protocol.md)"},
    {"delay-ms", "MS", K::Number, "0", "serve client", "network",
     "impair what this side receives: added delay"},
    {"jitter-ms", "MS", K::Number, "0", "serve client", "network",
     "impair what this side receives: random extra delay up to MS"},
    {"reorder", "P", K::Number, "0", "serve client", "network",
     "impair what this side receives: reordering probability 0..1"},

    // Acquisition (app/commands/acquire.cpp, docs/scan-format.md).
    {"out", "DATASET_DIR", K::Path, "", "acquire", "acquire",
     "the dataset folder to write (with --synthetic: the scan folder)"},
    {"synthetic", "KIND", K::Text, "", "acquire", "acquire",
     "simulate a scan of KIND (pattern_board, relief_ceramic_tile, plastic_grid, ...; a wrong KIND lists them)"},
    {"jobs", "N", K::Integer, "0", "acquire", "acquire",
     "threads, 0..256 (0: every core)"},
    {"force", "", K::Flag, "", "acquire export convert", "acquire",
     "replace an existing output"},
    {"compat", "paper|reference", K::Choice, "paper", "acquire", "acquire",
     "the paper's method, or the authors' code's (docs/scan-format.md)"},
    {"no-float-map", "", K::Flag, "", "acquire", "acquire",
     "no NAME_map.f32 beside the PNG map"},
    {"no-waveforms", "", K::Flag, "", "acquire", "acquire",
     "no measured per-taxel waveforms"},
    {"waveform-ms", "MS", K::Number, "0", "acquire", "acquire",
     "waveform length per taxel (0: the time the stylus takes to cross one)"},
    {"name", "NAME", K::Text, "", "acquire", "acquire",
     "--synthetic: the object's name (default: KIND)"},
    {"length-mm", "L", K::Number, "100", "acquire", "acquire",
     "--synthetic: scanned length, 1..1000 mm"},
    {"lines", "N", K::Integer, "50", "acquire", "acquire",
     "--synthetic: scan lines, 1..2000"},
    {"passes", "N", K::Integer, "8", "acquire", "acquire",
     "--synthetic: passes per line, 1..100"},
    {"seed", "N", K::Integer, "1", "acquire", "acquire",
     "--synthetic: random seed"},
    {"noise-g", "G", K::Number, "0.01", "acquire", "acquire",
     "--synthetic: accelerometer noise, 0..10 g"},
    {"photo", "WxH", K::Size, "640x480", "acquire", "acquire",
     "--synthetic: photo size"},
    {"scale", "PX_PER_MM", K::Number, "2.5", "acquire", "acquire",
     "--synthetic: top view scale, 0.1..100 px/mm"},
    {"both-directions", "", K::Flag, "", "acquire", "acquire",
     "--synthetic: also scan lines along X"},
    {"target-views", "N", K::Integer, "0", "acquire", "acquire",
     "--synthetic: extra photos of a planar target in tilted poses, 0..24"},
    {"authors-rig", "", K::Flag, "", "acquire", "acquire",
     "--synthetic: the camera the authors' code calibrates (so their run.py can process the scan)"},
    {"focal-px", "F[,STD]", K::Text, "", "acquire", "acquire",
     "a prior on the focal length in pixels (STD default 2 % of F): what one target view cannot determine"},

    // Statistics, export, playback, devices.
    {"out", "DIR", K::Path, "", "stats", "tools",
     "statistics.csv and statistics.json into DIR instead of CSV on stdout"},
    {"out", "FILE", K::Path, "", "convert", "tools",
     "the file to write; its extension picks the format (.hjif .ahap .haptic .wav)"},
    {"out", "FILE", K::Path, "", "export", "tools",
     "the file to write; its extension picks the format (.glb .gltf .hjif .ahap .haptic)"},
    {"hand-template", "", K::Flag, "", "export", "tools",
     "the generated hand as a glTF skin, to start a --hand-model from"},
    {"vid", "HEX", K::Text, "1209", "devices", "tools",
     "the gloves' USB vendor id"},
    {"pid", "HEX", K::Text, "0001", "devices", "tools",
     "the gloves' USB product id"},

    // Help and global options (app/main.cpp, app/commands/help.cpp).
    {"man", "", K::Flag, "", "help", "meta",
     "the manual page (troff), generated from this table"},
    {"check", "", K::Flag, "", "help", "meta",
     "check the option table against what each command reads (for maintainers)"},
    {"log", "debug|info|warn|error|off", K::Choice, "", "global", "meta",
     "log level (default: $VT_LOG, else info)"},
    {"help", "", K::Flag, "", "global", "meta",
     "the command's options (also -h; vtouching help COMMAND)"},
};
// clang-format on

constexpr OptionTable kTable{kSections, kCommands, kOptions};

}  // namespace

const OptionTable& optionTable() { return kTable; }

std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find(separator, start), text.size());
    if (end > start) out.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

std::vector<std::string_view> lines(std::string_view text) { return split(text, '\n'); }
std::vector<std::string_view> words(std::string_view text) { return split(text, ' '); }

bool takes(const OptionSpec& option, std::string_view command) {
  const auto list = words(option.commands);
  return option.commands == "global" || std::find(list.begin(), list.end(), command) != list.end();
}

const OptionSpec* findOption(const OptionTable& table, std::string_view command, std::string_view name) {
  for (const OptionSpec& option : table.options) {
    if (option.name == name && takes(option, command)) return &option;
  }
  return nullptr;
}

std::vector<const OptionSpec*> entriesNamed(const OptionTable& table, std::string_view name) {
  std::vector<const OptionSpec*> out;
  for (const OptionSpec& option : table.options) {
    if (option.name == name) out.push_back(&option);
  }
  return out;
}

std::vector<const OptionSpec*> optionsOf(const OptionTable& table, std::string_view command) {
  std::vector<const OptionSpec*> own, global;
  for (const OptionSpec& option : table.options) {
    if (option.commands == "global") global.push_back(&option);
    else if (takes(option, command)) own.push_back(&option);
  }
  own.insert(own.end(), global.begin(), global.end());
  return own;
}

const CommandSpec* findCommandSpec(const OptionTable& table, std::string_view name) {
  for (const CommandSpec& command : table.commands) {
    if (command.name == name) return &command;
  }
  return nullptr;
}

namespace {

// One alternative of a syntax: literal ("sim"), or a literal prefix before a placeholder or an
// optional part ("hid:SERIAL", "audio[:DEVICE]", "osc://HOST:PORT[?blocks]").
bool matchesAlternative(std::string_view alternative, std::string_view value) {
  const std::size_t open = std::find_if(alternative.begin(), alternative.end(), [](char c) {
                             return std::isupper(static_cast<unsigned char>(c)) || c == '[';
                           }) - alternative.begin();
  if (open == alternative.size()) return value == alternative;
  const std::string_view prefix = alternative.substr(0, open);
  if (value.substr(0, prefix.size()) != prefix) return false;
  return value.size() > prefix.size() || alternative[open] == '[';
}

template <class T>
bool parses(std::string_view text, T& out) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size();
}

}  // namespace

std::string checkValue(const OptionSpec& option, std::string_view value) {
  switch (option.kind) {
    case ValueKind::Flag:
      return value.empty() ? "" : str("--", option.name, " takes no value");
    case ValueKind::Text:
    case ValueKind::Path:
      return value.empty() ? str("--", option.name, " needs a value") : "";
    case ValueKind::Number: {
      double v = 0;
      return parses(value, v) && std::isfinite(v) ? "" : str("--", option.name, " expects a number, got '", value, "'");
    }
    case ValueKind::Integer: {
      int v = 0;
      return parses(value, v) ? "" : str("--", option.name, " expects an integer, got '", value, "'");
    }
    case ValueKind::Size: {
      const std::size_t x = value.find('x');
      int w = 0, h = 0;
      const bool ok = x != std::string_view::npos && parses(value.substr(0, x), w) && parses(value.substr(x + 1), h) &&
                      w > 0 && h > 0;
      return ok ? "" : str("--", option.name, " expects WxH, got '", value, "'");
    }
    case ValueKind::Choice:
      for (std::string_view alternative : split(option.value, '|')) {
        if (matchesAlternative(alternative, value)) return "";
      }
      return str("--", option.name, " '", value, "' is not ", option.value);
  }
  return "";
}

std::vector<std::string> literalChoices(const OptionSpec& option) {
  std::vector<std::string> out;
  if (option.kind != ValueKind::Choice) return out;
  for (std::string_view alternative : split(option.value, '|')) {
    const bool literal = std::none_of(alternative.begin(), alternative.end(), [](char c) {
      return std::isupper(static_cast<unsigned char>(c)) || c == '[' || c == ':' || c == '/';
    });
    if (literal) out.emplace_back(alternative);
  }
  return out;
}

}  // namespace vt::cli
