#include "vt/scene/gltf_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <nlohmann/json.hpp>

#include "gltf_haptic_material.hpp"
#include "vt/core/error.hpp"
#include "vt/core/output_file.hpp"

namespace vt {
namespace {

using nlohmann::json;

constexpr int kFloat = 5126, kUnsignedShort = 5123, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

Image16 mapAsImage16(const ImageF& map) {
  Image16 out(map.width, map.height, 1);
  // loadChannelAsFloat divides by 65535, so these values come back bit-exact.
  for (std::size_t i = 0; i < out.pixels.size(); ++i) {
    out.pixels[i] = std::uint16_t(std::lround(std::clamp(map.pixels[i * std::size_t(map.channels)], 0.0f, 1.0f) * 65535.0f));
  }
  return out;
}

bool isTranslation(const glm::mat4& m) {
  return m[0] == glm::vec4(1, 0, 0, 0) && m[1] == glm::vec4(0, 1, 0, 0) && m[2] == glm::vec4(0, 0, 1, 0) && m[3][3] == 1.0f;
}

class GltfWriter {
 public:
  GltfWriter(const Scene& scene, std::filesystem::path path, bool replace)
      : m_scene(scene), m_path(std::move(path)), m_replace(replace) {}

  void write() {
    const std::string ext = m_path.extension().string();
    if (ext != ".glb" && ext != ".gltf") fail("glTF export '", m_path.string(), "': the file must end in .glb or .gltf");
    m_binary = ext == ".glb";
    m_scene.validate();
    if (m_scene.objects.empty()) fail("glTF export '", m_path.string(), "': the scene has no objects");
    m_doc["asset"] = {{"version", "2.0"}, {"generator", "V-Touching"}};
    images();
    materials();
    objects();
    if (!m_scene.intensity.empty()) m_doc["extras"]["vtouching"]["intensity"] = m_scene.intensity;
    m_doc["buffers"] = json::array({{{"byteLength", m_bin.size()}}});
    if (!m_binary) m_doc["buffers"][0]["uri"] = sibling(".bin").filename().string();
    m_binary ? saveGlb() : saveGltf();
  }

 private:
  std::filesystem::path sibling(const std::string& suffix) const {
    return m_path.parent_path() / (m_path.stem().string() + suffix);
  }

  int bufferView(const void* data, std::size_t size, int target) {
    while (m_bin.size() % 4) m_bin.push_back(0);
    json view = {{"buffer", 0}, {"byteOffset", m_bin.size()}, {"byteLength", size}};
    if (target) view["target"] = target;
    m_bin.append(static_cast<const char*>(data), size);
    m_doc["bufferViews"].push_back(view);
    return int(m_doc["bufferViews"].size()) - 1;
  }

  int accessor(const std::vector<float>& values, int components, bool bounds) {
    static const char* kTypes[] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};
    const int view = bufferView(values.data(), values.size() * sizeof(float), kArrayBuffer);
    json a = {{"bufferView", view}, {"componentType", kFloat}, {"count", values.size() / std::size_t(components)},
              {"type", kTypes[components]}};
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

  int indexAccessor(const std::vector<std::uint32_t>& indices, std::size_t vertexCount) {
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

  // Images 0..T-1 are the colour textures, T.. the vibration maps; texture i shows image i.
  void images() {
    for (std::size_t i = 0; i < m_scene.textures.size(); ++i) image(encodePng(m_scene.textures[i]), str("texture_", i));
    for (std::size_t i = 0; i < m_scene.vibrationMaps.size(); ++i) {
      image(encodePng16(mapAsImage16(m_scene.vibrationMaps[i])), str("vibration_", i));
    }
  }

  void image(const std::vector<std::uint8_t>& png, const std::string& name) {
    json img = {{"name", name}};
    if (m_binary) {
      img["bufferView"] = bufferView(png.data(), png.size(), 0);
      img["mimeType"] = "image/png";
    } else {
      const std::filesystem::path file = sibling("_" + name + ".png");
      m_files.push_back({file, std::string(png.begin(), png.end())});
      img["uri"] = file.filename().string();
    }
    m_doc["images"].push_back(img);
    m_doc["textures"].push_back({{"source", m_doc["images"].size() - 1}});
  }

  void materials() {
    json haptic = json::array();
    for (const Material& m : m_scene.materials) {
      if (m.uvTransform != glm::mat3(1.0f)) fail("glTF export: material '", m.name, "' has a UV transform (not exported)");
      json pbr = {{"metallicFactor", 0.0}, {"roughnessFactor", 1.0}};
      if (m.baseColor != glm::vec4(1.0f)) pbr["baseColorFactor"] = {m.baseColor.r, m.baseColor.g, m.baseColor.b, m.baseColor.a};
      if (m.albedoTexture >= 0) pbr["baseColorTexture"] = {{"index", m.albedoTexture}};
      m_doc["materials"].push_back({{"name", m.name}, {"pbrMetallicRoughness", pbr}});
      m_haptic.push_back(m.vibrationMap < 0 ? -1 : int(haptic.size()));
      if (m.vibrationMap < 0) continue;
      const std::size_t texture = m_scene.textures.size() + std::size_t(m.vibrationMap);
      json ours = {{"gain", m.tactileGain}, {"wrap", m.wrapUv}, {"physical_width_m", m.physicalWidth_m},
                   {"scan_direction_uv", {m.scanDirectionUv.x, m.scanDirectionUv.y}}};
      if (m.vibrationMapAcross >= 0) ours["across_texture"] = m_scene.textures.size() + std::size_t(m.vibrationMapAcross);
      haptic.push_back({{"name", m.name},
                        {"vibrotactileTexture", json::array({{{"texture", {{"index", texture}}}, {"type", "High_Resolution"}}})},
                        {"extras", {{"vtouching", ours}}}});
    }
    if (haptic.empty()) return;
    m_doc["extensionsUsed"] = {gltf::kHapticMaterialExtension};
    m_doc["extensions"][gltf::kHapticMaterialExtension] = {{"materials", haptic}};
  }

  // One node and one mesh per object: the loader makes one scene mesh per node either way, and a
  // mesh carries the haptic material reference.
  void objects() {
    json nodes = json::array();
    for (const SceneObject& o : m_scene.objects) {
      const Mesh& mesh = m_scene.meshes[std::size_t(o.mesh)];
      if (mesh.vertices.empty() || mesh.indices.empty()) fail("glTF export: object '", o.name, "' has an empty mesh");
      std::vector<float> p, n, uv;
      for (const Vertex& v : mesh.vertices) {
        p.insert(p.end(), {v.position.x, v.position.y, v.position.z});
        n.insert(n.end(), {v.normal.x, v.normal.y, v.normal.z});
        uv.insert(uv.end(), {v.uv.x, 1.0f - v.uv.y});  // glTF's v runs down the image
      }
      json attributes = {{"POSITION", accessor(p, 3, true)}, {"NORMAL", accessor(n, 3, false)},
                         {"TEXCOORD_0", accessor(uv, 2, false)}};
      json primitive = {{"attributes", attributes}, {"indices", indexAccessor(mesh.indices, mesh.vertices.size())},
                        {"material", o.material}};
      json gltfMesh = {{"name", o.name}, {"primitives", json::array({primitive})}};
      if (const int h = m_haptic[std::size_t(o.material)]; h >= 0) {
        gltfMesh["extensions"][gltf::kHapticMaterialExtension] = {{"hapticMaterialIndex", h}};
      }
      m_doc["meshes"].push_back(gltfMesh);
      json node = {{"name", o.name}, {"mesh", m_doc["meshes"].size() - 1}};
      const glm::mat4& T = o.T_world_object;
      if (isTranslation(T)) {
        if (T[3] != glm::vec4(0, 0, 0, 1)) node["translation"] = {T[3].x, T[3].y, T[3].z};
      } else {
        node["matrix"] = json::array();
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r) node["matrix"].push_back(T[c][r]);
      }
      nodes.push_back(node);
      m_doc["scenes"][0]["nodes"].push_back(nodes.size() - 1);
    }
    m_doc["nodes"] = nodes;
    m_doc["scene"] = 0;
  }

  // Every file of the export appears together, or none does (vt::writeFiles).
  void saveGltf() {
    m_files.push_back({sibling(".bin"), std::move(m_bin)});
    m_files.push_back({m_path, m_doc.dump(1)});
    writeFiles(m_files, m_replace);
  }

  void saveGlb() {
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
    writeFiles({{m_path, std::move(out)}}, m_replace);
  }

  const Scene& m_scene;
  std::filesystem::path m_path;
  bool m_replace;
  bool m_binary = true;
  json m_doc = json::object();
  std::string m_bin;
  std::vector<FileContent> m_files;  // .gltf: the images beside it, then .bin and the JSON
  std::vector<int> m_haptic;  // per scene material: index in the haptic material list, -1 none
};

}  // namespace

void saveGltfScene(const Scene& scene, const std::filesystem::path& path, bool replace) {
  GltfWriter(scene, path, replace).write();
}

}  // namespace vt
