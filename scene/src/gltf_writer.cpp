#include "vt/scene/gltf_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <nlohmann/json.hpp>

#include "gltf_document.hpp"
#include "gltf_haptic_material.hpp"
#include "vt/core/error.hpp"
#include "vt/core/output_file.hpp"

namespace vt {
namespace {

using nlohmann::json;

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
      : m_scene(scene), m_gltf(std::move(path)), m_doc(m_gltf.doc()), m_replace(replace) {}

  void write() {
    m_scene.validate();
    if (m_scene.objects.empty()) fail("glTF export '", m_gltf.path().string(), "': the scene has no objects");
    images();
    materials();
    objects();
    if (!m_scene.intensity.empty()) m_doc["extras"]["vtouching"]["intensity"] = m_scene.intensity;
    m_gltf.save(m_replace);
  }

 private:
  // Images 0..T-1 are the colour textures, T.. the vibration maps; texture i shows image i.
  void images() {
    for (std::size_t i = 0; i < m_scene.textures.size(); ++i) image(encodePng(m_scene.textures[i]), str("texture_", i));
    for (std::size_t i = 0; i < m_scene.vibrationMaps.size(); ++i) {
      image(encodePng16(mapAsImage16(m_scene.vibrationMaps[i])), str("vibration_", i));
    }
  }

  void image(const std::vector<std::uint8_t>& png, const std::string& name) {
    json img = {{"name", name}};
    if (m_gltf.binary()) {
      img["bufferView"] = m_gltf.bufferView(png.data(), png.size(), 0);
      img["mimeType"] = "image/png";
    } else {
      const std::filesystem::path file = m_gltf.sibling("_" + name + ".png");
      m_gltf.addFile({file, std::string(png.begin(), png.end())});
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
      json attributes = {{"POSITION", m_gltf.accessor(p, 3, true)}, {"NORMAL", m_gltf.accessor(n, 3, false)},
                         {"TEXCOORD_0", m_gltf.accessor(uv, 2, false)}};
      json primitive = {{"attributes", attributes}, {"indices", m_gltf.indexAccessor(mesh.indices, mesh.vertices.size())},
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

  const Scene& m_scene;
  gltf::GltfDocument m_gltf;
  json& m_doc;
  bool m_replace;
  std::vector<int> m_haptic;  // per scene material: index in the haptic material list, -1 none
};

}  // namespace

void saveGltfScene(const Scene& scene, const std::filesystem::path& path, bool replace) {
  GltfWriter(scene, path, replace).write();
}

}  // namespace vt
