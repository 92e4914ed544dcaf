#include "modes/scene_source.hpp"

#include <algorithm>
#include <cerrno>

#include <unistd.h>

#include <sstream>

#include <nlohmann/json.hpp>

#include "vt/acquisition/scan.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/core/text_input.hpp"
#include "vt/core/log.hpp"
#include "vt/scene/demo_scene.hpp"
#include "vt/scene/loaders.hpp"

namespace vt::app {
namespace fs = std::filesystem;

namespace {
constexpr float kGratingPlate_m = 0.2f;  // --grating: the plate's side
}  // namespace

SceneOptions readSceneOptions(cli::Args& args) {
  SceneOptions options;
  options.gltf = args.valueOr("scene", "");
  options.dataset = args.valueOr("dataset", "");
  options.mmPerPixel = args.doubleOr("mm-per-pixel", 0.0);
  options.builtin = args.flag("builtin");
  options.grating_mm = args.doubleIn("grating", 0.0, 0.0, 50.0);
  const std::string intensity = args.valueOr("intensity", "absolute");
  if (intensity != "absolute" && intensity != "normalised") {
    fail(args.command(), ": --intensity expects absolute or normalised, got '", intensity, "'");
  }
  options.normalised = intensity == "normalised";
  options.gains = args.valueOr("gains", "");
  if (!options.gains.empty() && (!options.gltf.empty() || options.builtin || options.grating_mm > 0.0)) {
    fail(args.command(), ": --gains applies to dataset scenes, not --scene, --builtin or --grating");
  }
  options.allowOutsidePaths = args.flag("allow-outside-paths");
  if (!options.gltf.empty() + !options.dataset.empty() + options.builtin + (options.grating_mm > 0.0) > 1) {
    fail(args.command(), ": --scene, --dataset, --builtin and --grating exclude each other");
  }
  if (options.mmPerPixel < 0.0 || options.mmPerPixel > 100.0) {
    fail(args.command(), ": --mm-per-pixel ", options.mmPerPixel, " out of range 0..100");
  }
  return options;
}

fs::path defaultAssetsDir() {
  // An installed binary finds the copy installed beside it (<prefix>/share/vtouching/assets)
  // first, so it never depends on the source tree it was built from still being there.
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (const fs::path& candidate : {exe.parent_path() / "../share/vtouching/assets", exe.parent_path() / "assets"}) {
      if (fs::is_directory(candidate / "dataset")) return fs::weakly_canonical(candidate);
    }
  }
#ifdef VT_APP_SOURCE_DIR
  if (const fs::path source = fs::path(VT_APP_SOURCE_DIR) / "assets"; fs::is_directory(source / "dataset")) {
    return source;
  }
#endif
  return {};
}

namespace {

// A scene's path as the user reads it best (the description travels in a server's refusal,
// which has room for about 85 characters of it): relative to the working folder when shorter.
std::string displayPath(const fs::path& path) {
  std::error_code ec;
  const fs::path relative = fs::relative(path, fs::current_path(ec), ec);
  return !ec && !relative.empty() && relative.native().size() < path.native().size() ? relative.string() : path.string();
}

// A dataset is a folder: say what the path is instead (missing, a file, a loop, unreadable).
void checkDatasetFolder(const fs::path& dir) {
  std::error_code ec;
  const fs::file_status status = fs::status(dir, ec);
  if (status.type() == fs::file_type::directory) return;
  if (ec && ec.value() != ENOENT) throw Error(str("dataset ", describeErrno(dir, "read", ec.value())));
  if (status.type() == fs::file_type::not_found) fail("dataset folder '", dir.string(), "': not found");
  fail("dataset '", dir.string(), "': is a file, expected a folder with one sub-folder per object (docs/scan-format.md)");
}

// Per-taxel waveforms beside a dataset object replace its intensity-only map.
std::vector<haptics::VibrationMap> waveformMaps(const Scene& scene, const fs::path& datasetDir) {
  std::vector<haptics::VibrationMap> maps(scene.vibrationMaps.size());
  bool any = false;
  for (const Material& material : scene.materials) {
    const fs::path dir = datasetDir / material.name / "waveforms";
    std::error_code ec;
    if (material.vibrationMap < 0 || !fs::exists(dir / "header.bin", ec)) continue;
    // `vtouching acquire` says how long its waveforms are (waveforms.json); else the format's default.
    haptics::TaxelWaveformOptions waveformOptions;
    if (const fs::path info = dir / "waveforms.json"; fs::exists(info, ec)) {
      try {
        const std::string text = acq::readTextFile(info, "waveform description");
        checkJsonNesting(text, info.string(), budget::kJsonDepth);
        waveformOptions.samplesPerTaxel = nlohmann::json::parse(text).at("samples_per_taxel").get<int>();
      } catch (const nlohmann::json::exception& e) {
        fail(info.string(), ": field 'samples_per_taxel': ", e.what());
      }
    }
    maps[std::size_t(material.vibrationMap)] = haptics::loadTaxelWaveforms(dir, waveformOptions);
    log::info("scene: per-taxel waveforms for ", material.name, " from ", dir.string());
    any = true;
  }
  if (!any) maps.clear();
  return maps;
}

}  // namespace

LoadedScene loadScene(const SceneOptions& options) {
  LoadedScene out;
  Scene scene;
  std::vector<haptics::VibrationMap> waveforms;
  DatasetSceneOptions datasetOptions;
  datasetOptions.mmPerPixel = options.mmPerPixel;
  datasetOptions.intensity = options.normalised ? IntensityMode::Normalised : IntensityMode::Absolute;
  datasetOptions.gainsFile = options.gains;
  if (!options.gltf.empty()) {
    scene = loadGltfScene(options.gltf, {.allowOutsideFolder = options.allowOutsidePaths});
    out.description = str("glTF ", displayPath(options.gltf));
  } else if (!options.dataset.empty()) {
    checkDatasetFolder(options.dataset);
    scene = loadDatasetScene(options.dataset, datasetOptions);
    waveforms = waveformMaps(scene, options.dataset);
    out.description = str("dataset ", displayPath(options.dataset));
  } else if (options.grating_mm > 0.0) {
    // A calibration target: the felt frequency of a slide is its speed over the period.
    scene = makeGratingPlate(kGratingPlate_m, float(options.grating_mm * 1e-3));
    out.description = str("grating ", options.grating_mm, " mm");
  } else if (const fs::path assets = options.builtin ? fs::path() : defaultAssetsDir(); !assets.empty()) {
    scene = loadDatasetScene(assets / "dataset", datasetOptions);
    waveforms = waveformMaps(scene, assets / "dataset");
    out.description = str("assets ", displayPath(assets / "dataset"));
  } else {
    if (!options.builtin) log::warn("scene: no assets folder found, using the built-in demo scene");
    scene = makeDemoScene();
    out.description = "built-in demo scene";
  }
  for (const std::string& line : scene.unused) log::warn("scene: ", line);
  // Objects the hand can feel: the table (no vibration map) is not counted. The HUD line keeps
  // the intensity mode's first word (absolute / normalised) and whether gains apply;
  // traces.json and exported files keep the full sentence (Scene::intensity).
  const auto tactile = std::count_if(scene.objects.begin(), scene.objects.end(), [&](const SceneObject& o) {
    return scene.materials[std::size_t(o.material)].vibrationMap >= 0;
  });
  const std::string mode = scene.intensity.substr(0, scene.intensity.find(' ')) +
                           (scene.intensity.find(" x gains ") != std::string::npos ? " x gains" : "");
  out.description += str(" (", tactile, " objects", mode.empty() ? "" : ", intensity ", mode, ")");
  auto shared = std::make_shared<const Scene>(std::move(scene));
  out.haptic = haptics::makeHapticScene(shared, std::move(waveforms));
  out.scene = std::move(shared);
  return out;
}

std::string encodeSceneOptions(const SceneOptions& options) {
  // Paths go last on their own keys so spaces survive; one key per line would be overkill.
  std::ostringstream line;
  line << "mm_per_pixel=" << options.mmPerPixel << " builtin=" << int(options.builtin)
       << " gltf=" << options.gltf.size() << ':' << options.gltf << " dataset=" << options.dataset.size() << ':'
       << options.dataset << " intensity=" << (options.normalised ? "normalised" : "absolute")
       << " gains=" << options.gains.size() << ':' << options.gains << " grating_mm=" << options.grating_mm;
  return line.str();
}

SceneOptions decodeSceneOptions(const std::string& line, const std::string& source) {
  SceneOptions options;
  std::istringstream in(line);
  int builtin = 0;
  auto readPath = [&](const char* key, std::string& out) {
    std::string label;
    std::size_t size = 0;
    char colon = 0;
    in >> std::ws;
    std::getline(in, label, '=');
    if (label != key || !(in >> size >> colon) || colon != ':') fail(source, ": scene line: expected ", key, "=N:PATH");
    if (size > budget::kPathBytes) fail(source, ": scene line: ", key, " path length ", size, " is over the limit of ", budget::kPathBytes);
    out.resize(size);
    in.read(out.data(), std::streamsize(size));
    if (!in) fail(source, ": scene line: ", key, " path shorter than its length");
  };
  std::string key;
  if (!(in >> std::ws && std::getline(in, key, '=') && key == "mm_per_pixel" && in >> options.mmPerPixel) ||
      !(options.mmPerPixel >= 0.0 && options.mmPerPixel <= 100.0)) {
    fail(source, ": scene line: expected mm_per_pixel= a number in 0..100");
  }
  if (!(in >> std::ws && std::getline(in, key, '=') && key == "builtin" && in >> builtin)) {
    fail(source, ": scene line: expected builtin=");
  }
  options.builtin = builtin != 0;
  readPath("gltf", options.gltf);
  readPath("dataset", options.dataset);
  // Recordings made before --intensity existed end here (and were normalised).
  if (!(in >> std::ws) || in.eof()) {
    options.normalised = true;
    return options;
  }
  std::string intensity;
  if (!(std::getline(in, key, '=') && key == "intensity" && in >> intensity) ||
      (intensity != "absolute" && intensity != "normalised")) {
    fail(source, ": scene line: expected intensity=absolute|normalised");
  }
  options.normalised = intensity == "normalised";
  readPath("gains", options.gains);
  if (!(in >> std::ws) || in.eof()) return options;  // recorded before --grating existed
  if (!(std::getline(in, key, '=') && key == "grating_mm" && in >> options.grating_mm) ||
      !(options.grating_mm >= 0.0 && options.grating_mm <= 50.0)) {
    fail(source, ": scene line: expected grating_mm= a number in 0..50");
  }
  return options;
}

}  // namespace vt::app
