#pragma once
// Writes a Scene as glTF 2.0 with its vibration maps in the MPEG_haptic_material extension
// (docs/scene-format.md). Setup thread only; throws vt::Error naming the file and the problem.
#include <filesystem>

#include "vt/scene/scene.hpp"

namespace vt {

/// `.glb`: one binary file with buffers and PNG images inside. `.gltf`: the JSON plus STEM.bin and
/// STEM_*.png beside it. One node and one mesh per object; textures as 8-bit PNG, vibration maps as
/// 16-bit grey PNG; gain, wrap and physical width in each haptic material's `extras.vtouching`.
/// Loading the result with loadGltfScene gives the same tactileDigest for scenes whose object
/// transforms are translations or TRS matrices and whose UVs are 0 or 1 (every dataset scene).
/// Every file appears whole, together; an existing one is refused (naming --force) unless `replace`.
void saveGltfScene(const Scene& scene, const std::filesystem::path& path, bool replace);

}  // namespace vt
