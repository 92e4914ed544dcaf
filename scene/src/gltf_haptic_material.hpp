#pragma once
// The glTF vendor extension MPEG_haptic_material (ISO/IEC 23090-14; KhronosGroup/glTF
// extensions/2.0/Vendor/MPEG_haptic_material), read side, and the tactile settings object shared
// with the older `extras.vtouching` form. Private to vt::scene; setup thread only.
#include <string>

#include <tiny_gltf.h>

#include "vt/scene/scene.hpp"

namespace vt::gltf {

/// The extension's name, in `extensionsUsed` and the extension maps.
inline constexpr const char* kHapticMaterialExtension = "MPEG_haptic_material";

/// Reads `gain`, `wrap` and `physical_width_m` from a tactile settings object into `out`;
/// `where` names the object in errors ("glTF 'a.gltf': material 'm' extras.vtouching").
void readTactileSettings(const tinygltf::Value& settings, const std::string& where, Material& out);

/// The haptic material a mesh refers to (`mesh.extensions.MPEG_haptic_material.hapticMaterialIndex`),
/// -1 when it has none. Throws vt::Error naming the mesh when the reference is malformed.
int hapticMaterialIndex(const tinygltf::Model& model, const tinygltf::Mesh& mesh, const std::string& source);

/// Applies haptic material `index` of the file-level extension to `out`: its vibrotactile texture
/// (else its `vibration` texture) becomes a vibration map in `scene`, its `extras.vtouching` the
/// tactile settings; the other haptic maps (stiffness, friction, temperature, custom) are listed in
/// `scene.unused`. Throws vt::Error naming the file, the haptic material and the field.
void applyHapticMaterial(const tinygltf::Model& model, int index, const std::string& source, Material& out,
                         Scene& scene);

/// The file's own `extras.vtouching.intensity` (how the exporter set the gains) into scene.intensity.
void readFileExtras(const tinygltf::Model& model, const std::string& source, Scene& scene);

}  // namespace vt::gltf
