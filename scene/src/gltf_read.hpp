#pragma once
// Reading glTF files, shared by the scene and hand-model loaders (private to vt::scene; setup
// thread only): parsing with file access confined to the file's folder and held to the budgets,
// and bounds-checked accessor reads. Every error starts with the source's name.
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "vt/core/error.hpp"
#include "vt/scene/loaders.hpp"

namespace vt::gltf {

/// Checks a glTF's JSON (`.glb`: its JSON chunk) before tinygltf parses it: nesting within
/// budget::kJsonDepth, at most budget::kGltfJsonValues values, every index a 32-bit integer.
/// Throws vt::Error naming `source` and the field.
void checkGltfJson(const std::string& bytes, bool binary, const std::string& source);

/// Parses glTF JSON (or `.glb` when `binary`); URIs resolve in `baseDir` and, unless
/// options.allowOutsideFolder, must stay inside it. Images decode through vt's PNG/JPEG path.
tinygltf::Model parseModel(const std::string& bytes, bool binary, const std::string& source,
                           const std::filesystem::path& baseDir, const GltfLoadOptions& options);

/// Checked reads from one parsed model.
class AccessorReader {
 public:
  AccessorReader(const tinygltf::Model& model, std::string source) : m_model(model), m_source(std::move(source)) {}

  /// items[index], or vt::Error "SOURCE: WHAT index I out of range".
  template <class T>
  const T& element(const std::vector<T>& items, int index, const char* what) const {
    if (index < 0 || std::size_t(index) >= items.size()) fail(m_source, ": ", what, " index ", index, " out of range");
    return items[std::size_t(index)];
  }

  /// The accessor's element count, its elements checked to lie inside its buffer (none is read):
  /// sizes are held to their budgets before anything is allocated for them.
  std::size_t count(int accessorIndex, const char* what) const;
  /// `count` elements of `components` floats (float or normalised unsigned data), all finite.
  std::vector<float> floats(int accessorIndex, int components, const char* what) const;
  /// Triangle indices, each below `vertexCount`.
  std::vector<std::uint32_t> indices(int accessorIndex, std::size_t vertexCount) const;
  /// Unsigned byte or short integers (not normalised), `components` per element (e.g. JOINTS_0).
  std::vector<std::uint32_t> uints(int accessorIndex, int components, const char* what) const;
  /// A node's local transform (matrix, or translation * rotation * scale).
  static glm::mat4 localTransform(const tinygltf::Node& node);
  const std::string& source() const { return m_source; }

 private:
  std::pair<const std::uint8_t*, std::size_t> view(const tinygltf::Accessor& acc, std::size_t elementSize,
                                                   const char* what) const;
  const tinygltf::Model& m_model;
  std::string m_source;
};

}  // namespace vt::gltf
