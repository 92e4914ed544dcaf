#pragma once
// Where the app's scene comes from: a glTF file, a dataset directory, or the default assets
// (the project's own synthetic scans) with the built-in demo scene as the last resort.
// Setup (main) thread only.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli.hpp"
#include "vt/haptics/haptic_scene.hpp"
#include "vt/haptics/vibration_map.hpp"
#include "vt/scene/scene.hpp"

namespace vt::app {

/// What the user asked for on the command line (all empty = the default scene).
struct SceneOptions {
  std::string gltf;         // --scene FILE.gltf|.glb
  std::string dataset;      // --dataset DIR (published Pixel2Taxel layout)
  double mmPerPixel = 0.0;  // --mm-per-pixel (0 = per object metadata, else the documented default)
  bool builtin = false;     // --builtin: the procedural demo scene, ignoring assets
  double grating_mm = 0.0;  // --grating MM: one plate with a stripe grating of this period (0 = none)
  bool normalised = false;  // --intensity normalised (default absolute where the dataset allows)
  std::string gains;        // --gains FILE: per-object gain table for dataset scenes
  bool allowOutsidePaths = false;  // --allow-outside-paths: glTF URIs may leave the scene's folder
};

/// Reads --scene, --dataset, --mm-per-pixel, --builtin, --grating, --intensity, --gains and
/// --allow-outside-paths (throws vt::Error on conflicts).
SceneOptions readSceneOptions(cli::Args& args);

/// The default assets folder: <exe>/../share/vtouching/assets (an installed binary) when it
/// exists, else the source tree's assets/ (compile-time path); empty when neither exists.
std::filesystem::path defaultAssetsDir();

/// A scene ready for rendering and touching.
struct LoadedScene {
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const haptics::HapticScene> haptic;
  std::string description;  // "dataset assets/dataset (9 objects, intensity absolute)", for logs and the HUD
};

/// Loads the scene (throws vt::Error naming the file and problem). A dataset object folder that
/// holds `waveforms/header.bin` + `waveforms/data.bin` gets per-taxel waveforms for its map.
LoadedScene loadScene(const SceneOptions& options);

/// One line that rebuilds the same SceneOptions (recordings store it) and its parser.
std::string encodeSceneOptions(const SceneOptions& options);
SceneOptions decodeSceneOptions(const std::string& line, const std::string& source);

}  // namespace vt::app
