#pragma once
// Scenes from files: glTF 2.0 with tactile materials, and directories in the published
// Pixel2Taxel layout. Every error names the file and the problem (vt::Error).
#include <filesystem>
#include <map>
#include <string>

#include "vt/scene/scene.hpp"

namespace vt {

struct GltfLoadOptions {
  /// Files named by URIs (buffers, images, vibration maps) must resolve, symlinks included, inside
  /// the glTF's folder unless this is set (`--allow-outside-paths`, for scenes the user trusts).
  bool allowOutsideFolder = false;
};

/// Loads a .gltf/.glb file. Triangle primitives become objects; a material's
/// `extras.vtouching` object may give `vibration_map` (path relative to the file), `gain`,
/// `wrap` and `physical_width_m` (docs/scene-format.md). Sizes are held to vt::budget.
Scene loadGltfScene(const std::filesystem::path& path, const GltfLoadOptions& options = {});

/// Same from bytes already in memory (`.glb` when `binary`); `sourceName` names it in errors.
Scene loadGltfScene(const std::string& bytes, bool binary, const std::string& sourceName,
                    const std::filesystem::path& baseDir, const GltfLoadOptions& options = {});

/// Throws vt::Error "WHAT 'PATH' is outside the scene folder" unless `path` resolves inside `folder`.
void checkInsideFolder(const std::filesystem::path& path, const std::filesystem::path& folder, const std::string& what);

/// How vibration intensities compare across a dataset's objects (docs/scene-format.md).
enum class IntensityMode {
  Absolute,    ///< undo each map's min-max normalisation with NAME_map.json (V_scale), one scale for all
  Normalised,  ///< every map as published: each object's strongest taxel is 1
};

struct DatasetSceneOptions {
  /// Physical size of one image pixel. 0 = per object from NAME/NAME_map.json
  /// (`mm_per_pixel`) when present, else estimated from the map's taxel rows
  /// (estimateMmPerPixel, logged), else kDefaultMmPerPixel.
  double mmPerPixel = 0.0;
  /// Load at most this many objects (0 = all), in alphabetical order.
  int maxObjects = 0;
  /// Absolute applies where NAME_map.json carries the normalisation; objects without it stay normalised.
  IntensityMode intensity = IntensityMode::Absolute;
  /// Optional per-object gain table (CSV `name,gain`), multiplied in after the intensity mode.
  std::filesystem::path gainsFile;
};

/// Reads a gain table: one `name,gain` line per object (a `name,gain` header and `#` comments
/// allowed), gains in [0, 20]. Throws vt::Error naming the file, the line and the problem.
std::map<std::string, float> loadGainTable(const std::filesystem::path& file);

/// The scale assumed when neither metadata nor a taxel pattern gives one. Override with
/// DatasetSceneOptions::mmPerPixel.
inline constexpr double kDefaultMmPerPixel = 0.3;

/// Builds a table with one plate per NAME/ folder holding NAME.png and NAME_acc.png
/// (photo as texture, map as vibration map, same size required).
Scene loadDatasetScene(const std::filesystem::path& dir, const DatasetSceneOptions& options = {});

}  // namespace vt
