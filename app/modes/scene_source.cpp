#include "modes/scene_source.hpp"

#include <algorithm>

#include <unistd.h>

#include <sstream>

#include <nlohmann/json.hpp>

#include "vt/acquisition/scan.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/scene/demo_scene.hpp"
#include "vt/scene/loaders.hpp"

namespace vt::app {
namespace fs = std::filesystem;

SceneOptions readSceneOptions(cli::Args& args) {
  SceneOptions options;
  options.gltf = args.valueOr("scene", "");
  options.dataset = args.valueOr("dataset", "");
  options.mmPerPixel = args.doubleOr("mm-per-pixel", 0.0);
  options.builtin = args.flag("builtin");
  const std::string intensity = args.valueOr("intensity", "absolute");
  if (intensity != "absolute" && intensity != "normalised") {
    fail(args.command(), ": --intensity expects absolute or normalised, got '", intensity, "'");
  }
  options.normalised = intensity == "normalised";
  options.gains = args.valueOr("gains", "");
  if (!options.gains.empty() && (!options.gltf.empty() || options.builtin)) {
    fail(args.command(), ": --gains applies to dataset scenes, not --scene or --builtin");
  }
  options.allowOutsidePaths = args.flag("allow-outside-paths");
  if (!options.gltf.empty() + !options.dataset.empty() + options.builtin > 1) {
    fail(args.command(), ": --scene, --dataset and --builtin exclude each other");
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
        waveformOptions.samplesPerTaxel = nlohmann::json::parse(acq::readTextFile(info, "waveform description")).at("samples_per_taxel").get<int>();
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
    out.description = str("glTF ", options.gltf);
  } else if (!options.dataset.empty()) {
    if (!fs::is_directory(options.dataset)) fail(options.dataset, ": dataset directory not found");
    scene = loadDatasetScene(options.dataset, datasetOptions);
    waveforms = waveformMaps(scene, options.dataset);
    out.description = str("dataset ", options.dataset);
  } else if (const fs::path assets = options.builtin ? fs::path() : defaultAssetsDir(); !assets.empty()) {
    scene = loadDatasetScene(assets / "dataset", datasetOptions);
    waveforms = waveformMaps(scene, assets / "dataset");
    out.description = str("assets ", (assets / "dataset").string());
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
       << " gains=" << options.gains.size() << ':' << options.gains;
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
  return options;
}

}  // namespace vt::app
