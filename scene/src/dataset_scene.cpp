#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "dataset_intensity.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/text_input.hpp"
#include "vt/core/file_io.hpp"
#include "vt/core/log.hpp"
#include "vt/scene/demo_scene.hpp"
#include "vt/scene/loaders.hpp"
#include "vt/scene/taxel_pitch.hpp"

namespace vt {
namespace {

// NAME_map.json (written by `vtouching acquire`), null when the object has none.
nlohmann::json objectMeta(const std::filesystem::path& folder, const std::string& name) {
  const auto metaPath = folder / (name + "_map.json");
  std::error_code ec;
  if (std::filesystem::symlink_status(metaPath, ec).type() == std::filesystem::file_type::not_found) return nullptr;
  // Present but a folder, a loop or unreadable: say so instead of falling back silently.
  const std::string text = readInputText(metaPath, "dataset metadata", budget::kTextFileBytes);
  checkJsonNesting(text, "dataset metadata '" + metaPath.string() + "'", budget::kJsonDepth);
  nlohmann::json meta = nlohmann::json::parse(text, nullptr, false);
  if (meta.is_discarded() || !meta.is_object()) fail("dataset metadata '", metaPath.string(), "': not valid JSON");
  return meta;
}

// The direction the main map was scanned along, in map UV: [1, 0] unless the metadata says.
glm::vec2 objectScanDirection(const nlohmann::json& meta, const std::filesystem::path& metaPath) {
  if (meta.is_null() || !meta.contains("scan_direction_uv")) return {1.0f, 0.0f};
  const nlohmann::json& d = meta["scan_direction_uv"];
  if (!d.is_array() || d.size() != 2 || !d[0].is_number() || !d[1].is_number()) {
    fail("dataset metadata '", metaPath.string(), "': field 'scan_direction_uv' must be [u, v]");
  }
  const glm::vec2 v(d[0].get<float>(), d[1].get<float>());
  const float n = glm::length(v);
  if (!(n > 0.0f) || !std::isfinite(n)) fail("dataset metadata '", metaPath.string(), "': field 'scan_direction_uv' is not a direction");
  return v / n;
}

double objectMmPerPixel(const nlohmann::json& meta, const std::filesystem::path& metaPath, double fallback) {
  if (meta.is_null()) return fallback;
  const auto it = meta.find("mm_per_pixel");
  // The acquisition pipeline writes [along x, along y]; plates are sized by the x value.
  const nlohmann::json value = it == meta.end() ? nlohmann::json() : it->is_array() && it->size() == 2 ? (*it)[0] : *it;
  // Plates are sized from it: 1e308 or 1e-300 would make infinite or vanishing geometry.
  if (!value.is_number() || !(value.get<double>() >= 1e-3 && value.get<double>() <= 100.0)) {
    fail("dataset metadata '", metaPath.string(), "': field 'mm_per_pixel' must be a number in [0.001, 100] (or [x, y])");
  }
  return value.get<double>();
}

// An object's scale: its NAME_map.json when present, else estimated from the map's taxel rows
// (printed, since the published data records none), else kDefaultMmPerPixel with a warning.
double datasetMmPerPixel(const nlohmann::json& meta, const std::filesystem::path& folder, const std::string& name,
                         const ImageF& map) {
  if (const double recorded = objectMmPerPixel(meta, folder / (name + "_map.json"), 0.0); recorded > 0.0) return recorded;
  if (const double estimated = estimateMmPerPixel(map); estimated > 0.0) {
    log::info("dataset object '", name, "': ", estimated, " mm per pixel, estimated from its taxel rows (--mm-per-pixel overrides)");
    return estimated;
  }
  log::warn("dataset object '", name, "': no taxel rows to estimate its scale from; ", kDefaultMmPerPixel,
            " mm per pixel assumed (--mm-per-pixel overrides)");
  return kDefaultMmPerPixel;
}

// A map PNG (0..1 over [min_g, max_g] of its range) as V / peak: one physical scale for both maps of
// a two-direction object. 0 stays 0 (no taxel; the weakest taxel's own pixels fall to 0 as well).
void toPeakScale(ImageF& map, const std::array<double, 2>& range_g, double peak_g) {
  const float lo = float(range_g[0] / peak_g), span = float((range_g[1] - range_g[0]) / peak_g);
  for (float& p : map.pixels) p = p > 0.0f ? lo + p * span : 0.0f;
}

}  // namespace

Scene loadDatasetScene(const std::filesystem::path& dir, const DatasetSceneOptions& options) {
  if (!std::filesystem::is_directory(dir)) fail("dataset '", dir.string(), "': not a directory");
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    std::error_code ec;
    if (entry.is_directory(ec) && std::filesystem::exists(entry.path() / (name + "_acc.png"), ec)) names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  if (names.empty()) {
    fail("dataset '", dir.string(), "': no NAME/NAME.png + NAME/NAME_acc.png pairs found");
  }
  if (options.maxObjects > 0 && int(names.size()) > options.maxObjects) names.resize(std::size_t(options.maxObjects));

  Scene scene;
  struct Placed {
    float width_m, depth_m;
  };
  std::vector<Placed> sizes;
  std::vector<nlohmann::json> metas;
  for (const std::string& name : names) {
    const auto folder = dir / name;
    const nlohmann::json& meta = metas.emplace_back(objectMeta(folder, name));
    Image8 photo = loadImage8(folder / (name + ".png"), 4);
    ImageF map = loadChannelAsFloat(folder / (name + "_acc.png"), 0);
    if (photo.width != map.width || photo.height != map.height) {
      fail("dataset object '", name, "': photo is ", photo.width, "x", photo.height, " but ", name,
           "_acc.png is ", map.width, "x", map.height, " (they must be pixel-aligned)");
    }
    const auto metaPath = folder / (name + "_map.json");
    const double mmPerPixel = options.mmPerPixel > 0.0 ? options.mmPerPixel : datasetMmPerPixel(meta, folder, name, map);
    const float width_m = float(photo.width * mmPerPixel * 1e-3);
    const float depth_m = float(photo.height * mmPerPixel * 1e-3);
    scene.textures.push_back(std::move(photo));
    scene.vibrationMaps.push_back(std::move(map));
    const int mapIndex = int(scene.vibrationMaps.size()) - 1;
    // A scan in two directions: the map scanned across, blended by the finger's direction.
    int acrossIndex = -1;
    if (const auto acrossPath = folder / (name + "_acc_across.png"); std::filesystem::exists(acrossPath)) {
      ImageF across = loadChannelAsFloat(acrossPath, 0);
      const ImageF& main = scene.vibrationMaps.back();
      if (across.width != main.width || across.height != main.height) {
        fail("dataset object '", name, "': ", name, "_acc_across.png is ", across.width, "x", across.height,
             " but the photo is ", main.width, "x", main.height, " (they must be pixel-aligned)");
      }
      // Each map has its own range in NAME_map.json (older datasets shared the main map's).
      if (const double peak = twoDirectionPeak_g(meta); peak > 0.0) {
        toPeakScale(scene.vibrationMaps.back(), *pngRange_g(meta, false), peak);
        toPeakScale(across, *pngRange_g(meta, true), peak);
      }
      scene.vibrationMaps.push_back(std::move(across));
      acrossIndex = int(scene.vibrationMaps.size()) - 1;
    }
    scene.meshes.push_back(makeBox({width_m, 0.004f, depth_m}));
    scene.materials.push_back({.name = name,
                               .albedoTexture = int(scene.textures.size()) - 1,
                               .vibrationMap = mapIndex,
                               .physicalWidth_m = width_m,
                               .vibrationMapAcross = acrossIndex,
                               .scanDirectionUv = objectScanDirection(meta, metaPath)});
    sizes.push_back({width_m, depth_m});
  }
  applyDatasetIntensity(scene, names, metas, options);

  // Lay the plates out in rows of up to four, 3 cm apart, centred on the table.
  constexpr float kGap_m = 0.03f;
  const std::size_t perRow = std::min<std::size_t>(4, names.size());
  std::vector<float> rowWidth, rowDepth;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    if (i % perRow == 0) {
      rowWidth.push_back(-kGap_m);
      rowDepth.push_back(0.0f);
    }
    rowWidth.back() += sizes[i].width_m + kGap_m;
    rowDepth.back() = std::max(rowDepth.back(), sizes[i].depth_m);
  }
  float totalDepth = -kGap_m;
  for (float d : rowDepth) totalDepth += d + kGap_m;
  float z = -totalDepth * 0.5f;
  for (std::size_t row = 0; row < rowWidth.size(); ++row) {
    float x = -rowWidth[row] * 0.5f;
    for (std::size_t i = row * perRow; i < std::min(sizes.size(), (row + 1) * perRow); ++i) {
      const glm::vec3 centre{x + sizes[i].width_m * 0.5f, 0.002f, z + rowDepth[row] * 0.5f};
      scene.objects.push_back({names[i], int(i), int(i), glm::translate(glm::mat4(1.0f), centre)});
      x += sizes[i].width_m + kGap_m;
    }
    z += rowDepth[row] + kGap_m;
  }

  float maxRow = 0.0f;
  for (float w : rowWidth) maxRow = std::max(maxRow, w);
  scene.meshes.push_back(makeBox({maxRow + 0.2f, 0.04f, totalDepth + 0.2f}));
  scene.textures.push_back(makePatternTexture(Pattern::Wood, 256, {0.45f, 0.28f, 0.15f}, {0.62f, 0.42f, 0.25f}));
  scene.materials.push_back({.name = "table", .albedoTexture = int(scene.textures.size()) - 1});
  scene.objects.push_back({"table", int(scene.meshes.size()) - 1, int(scene.materials.size()) - 1,
                           glm::translate(glm::mat4(1.0f), {0.0f, -0.02f, 0.0f})});

  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.distance_m = std::max(0.4f, 0.9f * std::max(maxRow, totalDepth) + 0.15f);
  scene.camera.pitch_rad = -1.0f;
  scene.validate();
  return scene;
}

}  // namespace vt
