// `vtouching export`: a dataset (or any scene) as glTF with MPEG_haptic_material, or an actuator
// recording as HJIF / AHAP / Meta .haptic (docs/scene-format.md, docs/haptic-files.md).
#include <algorithm>
#include <cstdio>

#include "cli.hpp"
#include "modes/scene_source.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/files/haptic_formats.hpp"
#include "vt/scene/gltf_writer.hpp"
#include "vt/scene/hand_mesh.hpp"

namespace {

int exportRecording(const std::vector<std::string>& inputs, const std::filesystem::path& out, bool force) {
  std::filesystem::path csv, wav;
  for (const std::string& input : inputs) {
    const std::string ext = std::filesystem::path(input).extension().string();
    std::filesystem::path& slot = ext == ".csv" ? csv : ext == ".wav" ? wav : csv;
    if ((ext != ".csv" && ext != ".wav") || !slot.empty()) {
      vt::fail("export: recordings are one --record-csv file and/or one --record-wav file, got '", input, "'");
    }
    slot = input;
  }
  const vt::LoadScope loading("recording '" + (csv.empty() ? wav : csv).string() + "'");
  const auto clip = vt::haptics::files::loadRecording(csv, wav);
  for (const auto& file : vt::haptics::files::saveHapticFile(clip, out, force)) std::printf("wrote %s\n", file.c_str());
  return 0;
}

}  // namespace

VT_COMMAND(export) {
  const auto out = args.value("out");
  const bool force = args.flag("force");
  if (args.flag("hand-template")) {  // the generated hand, a template for --hand-model (docs/renderer.md)
    args.finish();
    if (!out) vt::fail("export: --hand-template needs --out HAND.glb|.gltf");
    vt::saveHandModel(vt::makeHandMesh(), *out, force);
    std::printf("wrote %s: the generated right hand, skinned to the 26 OpenXR hand joints\n", out->c_str());
    return 0;
  }
  vt::app::SceneOptions scene = vt::app::readSceneOptions(args);
  const auto positional = args.positionals();
  args.finish();
  if (!out) vt::fail("export: --out FILE is required (.glb, .gltf, .hjif, .ahap or .haptic)");
  const std::string ext = std::filesystem::path(*out).extension().string();
  if (ext == ".hjif" || ext == ".ahap" || ext == ".haptic") {
    if (positional.empty()) vt::fail("export: give the recording's CSV and/or WAV (from --record-csv / --record-wav)");
    return exportRecording(positional, *out, force);
  }
  const bool recording = !positional.empty() && std::all_of(positional.begin(), positional.end(), [](const std::string& p) {
    const std::string e = std::filesystem::path(p).extension().string();
    return e == ".csv" || e == ".wav";
  });
  if (ext != ".glb" && ext != ".gltf") {
    vt::fail("export: --out '", *out, "': unknown extension '", ext, "': a ", recording ? "recording" : "scene",
             " exports to ", recording ? ".hjif, .ahap or .haptic" : ".glb or .gltf",
             recording ? "" : " (and an actuator recording to .hjif, .ahap or .haptic)");
  }
  if (recording) {
    vt::fail("export: '", positional[0], "' is an actuator recording: export it to .hjif, .ahap or .haptic, not ", ext);
  }
  if (positional.size() > 1) vt::fail("export: expected one DATASET_DIR");
  if (positional.size() == 1) {
    if (!scene.gltf.empty() || scene.builtin) vt::fail("export: DATASET_DIR and --scene/--builtin exclude each other");
    scene.dataset = positional[0];
  }
  const vt::app::LoadedScene loaded = vt::app::loadScene(scene);
  vt::saveGltfScene(*loaded.scene, *out, force);
  std::printf("wrote %s: %s\n", out->c_str(), loaded.description.c_str());
  return 0;
}
