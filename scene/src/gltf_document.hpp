#pragma once
// A glTF document being written, shared by the scene and hand-model exporters (private to
// vt::scene; setup thread only): the JSON, one binary buffer, accessors, and saving as .glb or as
// .gltf + .bin (+ side files), every file whole or none.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "vt/core/output_file.hpp"

namespace vt::gltf {

inline constexpr int kUnsignedByte = 5121, kFloat = 5126, kUnsignedShort = 5123, kUnsignedInt = 5125;
inline constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

class GltfDocument {
 public:
  /// Throws vt::Error "glTF export 'PATH': the file must end in .glb or .gltf" for other names.
  explicit GltfDocument(std::filesystem::path path);

  nlohmann::json& doc() { return m_doc; }
  bool binary() const { return m_binary; }
  const std::filesystem::path& path() const { return m_path; }
  /// PATH's folder / (PATH's stem + suffix), for side files.
  std::filesystem::path sibling(const std::string& suffix) const;
  /// Appends bytes to the buffer (4-byte aligned) as a new bufferView; `target` 0 = none.
  int bufferView(const void* data, std::size_t size, int target);
  /// A float accessor of `components` (1-4, or 16 for MAT4) per element; min/max when `bounds`.
  int accessor(const std::vector<float>& values, int components, bool bounds);
  /// Triangle indices as unsigned short when the vertices allow, else unsigned int.
  int indexAccessor(const std::vector<std::uint32_t>& indices, std::size_t vertexCount);
  /// A file written beside a .gltf (e.g. an image), together with it.
  void addFile(FileContent file) { m_files.push_back(std::move(file)); }
  /// Writes the document (refuses existing files unless `replace`).
  void save(bool replace);

 private:
  std::filesystem::path m_path;
  bool m_binary = true;
  nlohmann::json m_doc = nlohmann::json::object();
  std::string m_bin;
  std::vector<FileContent> m_files;
};

}  // namespace vt::gltf
