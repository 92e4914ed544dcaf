#include "gltf_document.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "vt/core/error.hpp"

namespace vt::gltf {

using nlohmann::json;

GltfDocument::GltfDocument(std::filesystem::path path) : m_path(std::move(path)) {
  const std::string ext = m_path.extension().string();
  if (ext != ".glb" && ext != ".gltf") fail("glTF export '", m_path.string(), "': the file must end in .glb or .gltf");
  m_binary = ext == ".glb";
  m_doc["asset"] = {{"version", "2.0"}, {"generator", "V-Touching"}};
}

std::filesystem::path GltfDocument::sibling(const std::string& suffix) const {
  return m_path.parent_path() / (m_path.stem().string() + suffix);
}

int GltfDocument::bufferView(const void* data, std::size_t size, int target) {
  while (m_bin.size() % 4) m_bin.push_back(0);
  json view = {{"buffer", 0}, {"byteOffset", m_bin.size()}, {"byteLength", size}};
  if (target) view["target"] = target;
  m_bin.append(static_cast<const char*>(data), size);
  m_doc["bufferViews"].push_back(view);
  return int(m_doc["bufferViews"].size()) - 1;
}

int GltfDocument::accessor(const std::vector<float>& values, int components, bool bounds) {
  const char* type = components == 16 ? "MAT4" : std::array{"", "SCALAR", "VEC2", "VEC3", "VEC4"}[std::size_t(components)];
  // Inverse bind matrices have no buffer view target (they are not vertex data).
  const int view = bufferView(values.data(), values.size() * sizeof(float), components == 16 ? 0 : kArrayBuffer);
  json a = {{"bufferView", view}, {"componentType", kFloat}, {"count", values.size() / std::size_t(components)},
            {"type", type}};
  if (bounds) {
    std::vector<float> lo(std::size_t(components), INFINITY), hi(std::size_t(components), -INFINITY);
    for (std::size_t i = 0; i < values.size(); ++i) {
      lo[i % std::size_t(components)] = std::min(lo[i % std::size_t(components)], values[i]);
      hi[i % std::size_t(components)] = std::max(hi[i % std::size_t(components)], values[i]);
    }
    a["min"] = lo, a["max"] = hi;
  }
  m_doc["accessors"].push_back(a);
  return int(m_doc["accessors"].size()) - 1;
}

int GltfDocument::indexAccessor(const std::vector<std::uint32_t>& indices, std::size_t vertexCount) {
  int view = 0, type = kUnsignedInt;
  if (vertexCount <= 0xFFFF) {
    const std::vector<std::uint16_t> narrow(indices.begin(), indices.end());
    view = bufferView(narrow.data(), narrow.size() * 2, kElementArrayBuffer), type = kUnsignedShort;
  } else {
    view = bufferView(indices.data(), indices.size() * 4, kElementArrayBuffer);
  }
  m_doc["accessors"].push_back({{"bufferView", view}, {"componentType", type}, {"count", indices.size()}, {"type", "SCALAR"}});
  return int(m_doc["accessors"].size()) - 1;
}

// Every file of the export appears together, or none does (vt::writeFiles).
void GltfDocument::save(bool replace) {
  m_doc["buffers"] = json::array({{{"byteLength", m_bin.size()}}});
  if (m_binary) {
    std::string text = m_doc.dump();
    while (text.size() % 4) text.push_back(' ');
    while (m_bin.size() % 4) m_bin.push_back(0);
    std::string out;
    auto u32 = [&](std::uint32_t v) {
      for (int i = 0; i < 4; ++i) out.push_back(char(v >> (8 * i)));
    };
    u32(0x46546C67), u32(2), u32(std::uint32_t(12 + 8 + text.size() + 8 + m_bin.size()));
    u32(std::uint32_t(text.size())), u32(0x4E4F534A);
    out += text;
    u32(std::uint32_t(m_bin.size())), u32(0x004E4942);
    out += m_bin;
    writeFiles({{m_path, std::move(out)}}, replace);
  } else {
    m_doc["buffers"][0]["uri"] = sibling(".bin").filename().string();
    m_files.push_back({sibling(".bin"), std::move(m_bin)});
    m_files.push_back({m_path, m_doc.dump(1)});
    writeFiles(m_files, replace);
  }
}

}  // namespace vt::gltf
