#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "gltf_haptic_material.hpp"
#include "gltf_read.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/scene/loaders.hpp"

namespace vt {
namespace {

class GltfConverter {
 public:
  GltfConverter(const tinygltf::Model& model, std::string source, std::filesystem::path baseDir,
                const GltfLoadOptions& options)
      : m_model(model), m_source(std::move(source)), m_read(model, m_source), m_baseDir(std::move(baseDir)),
        m_options(options) {}

  Scene convert() {
    if (m_model.scenes.empty()) fail(m_source, ": the file has no scene");
    const int sceneIndex = m_model.defaultScene >= 0 ? m_model.defaultScene : 0;
    if (std::size_t(sceneIndex) >= m_model.scenes.size()) fail(m_source, ": default scene ", sceneIndex, " missing");
    for (int node : m_model.scenes[std::size_t(sceneIndex)].nodes) visit(node, glm::mat4(1.0f), 0);
    checkInstancedSize();
    // Each glTF mesh is read once, and copied per instance (within the budget checked above).
    std::map<int, std::vector<Primitive>> meshes;
    std::map<int, std::size_t> usesLeft;  // the last instance of a mesh takes it (no extra copy)
    for (const Instance& instance : m_instances) {
      auto [it, isNew] = meshes.try_emplace(instance.mesh);
      if (isNew) it->second = readMesh(m_model.meshes[std::size_t(instance.mesh)]);
      ++usesLeft[instance.mesh];
    }
    for (const Instance& instance : m_instances) {
      const tinygltf::Mesh& mesh = m_model.meshes[std::size_t(instance.mesh)];
      const int haptic = gltf::hapticMaterialIndex(m_model, mesh, m_source);
      const bool last = --usesLeft[instance.mesh] == 0;
      for (Primitive& p : meshes[instance.mesh]) {
        m_scene.meshes.push_back(last ? std::move(p.mesh) : p.mesh);
        m_scene.objects.push_back({instance.name.empty() ? mesh.name : instance.name, int(m_scene.meshes.size()) - 1,
                                   material(p.material, haptic), instance.T_world_node});
      }
    }
    if (m_scene.objects.empty()) fail(m_source, ": no triangle meshes in the scene");
    gltf::readFileExtras(m_model, m_source, m_scene);
    m_scene.validate();
    return std::move(m_scene);
  }

 private:
  // A node's use of a mesh, and one triangle primitive of a mesh read from its accessors.
  struct Instance {
    int mesh;
    std::string name;
    glm::mat4 T_world_node;
  };
  struct Primitive {
    Mesh mesh;
    int material;
  };

  // The vertices and indices of every mesh instance together, from the accessors' counts before
  // any is read: a small file can list one mesh many times, or one accessor can hold a
  // gigabyte (each count checked against its buffer first).
  void checkInstancedSize() {
    constexpr std::uint64_t kOver = std::uint64_t(1) << 62;  // saturates: counts come from the file
    std::map<int, std::pair<std::uint64_t, std::uint64_t>> perMesh;
    std::uint64_t vertices = 0, indices = 0;
    for (const Instance& instance : m_instances) {
      auto [it, isNew] = perMesh.try_emplace(instance.mesh);
      if (isNew) {
        for (const tinygltf::Primitive& prim : m_model.meshes[std::size_t(instance.mesh)].primitives) {
          if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;
          const auto pos = prim.attributes.find("POSITION");
          if (pos == prim.attributes.end()) continue;  // readMesh names it
          const std::uint64_t v = std::min<std::uint64_t>(m_read.count(pos->second, "POSITION"), kOver);
          const std::uint64_t i = prim.indices >= 0 ? std::min<std::uint64_t>(m_read.count(prim.indices, "indices"), kOver) : v;
          it->second.first = std::min(it->second.first + v, kOver);
          it->second.second = std::min(it->second.second + i, kOver);
        }
      }
      vertices = std::min(vertices + it->second.first, kOver);
      indices = std::min(indices + it->second.second, kOver);
      const bool tooMany = vertices > budget::kSceneVertices;
      if (tooMany || indices > budget::kSceneIndices) {
        fail(m_source, ": the scene's ", m_instances.size(), " mesh instances hold more than ",
             tooMany ? budget::kSceneVertices : budget::kSceneIndices, tooMany ? " vertices" : " indices",
             m_instances.size() > 1 ? " (one mesh used by many nodes?)" : "", " (docs/RELIABILITY.md)");
      }
    }
  }

  void visit(int nodeIndex, const glm::mat4& T_world_parent, int depth) {
    if (depth > 64) fail(m_source, ": node hierarchy deeper than 64 (a cycle?)");
    // Depth alone does not bound the work: a node listing its child twice doubles it per level.
    if (++m_visits > budget::kSceneNodeVisits) {
      fail(m_source, ": more than ", budget::kSceneNodeVisits, " node visits (nodes listed as children many times?)");
    }
    const tinygltf::Node& node = m_read.element(m_model.nodes, nodeIndex, "node");
    const glm::mat4 local = m_read.localTransform(node);
    const glm::mat4 T_world_node = T_world_parent * local;
    for (int i = 0; i < 16; ++i) {
      if (!std::isfinite(glm::value_ptr(T_world_node)[i])) {
        fail(m_source, ": node ", nodeIndex, " has a NaN or infinite transform");
      }
    }
    if (node.mesh >= 0) {
      m_read.element(m_model.meshes, node.mesh, "mesh");
      m_instances.push_back({node.mesh, node.name, T_world_node});
    }
    for (int child : node.children) visit(child, T_world_node, depth + 1);
  }

  std::vector<Primitive> readMesh(const tinygltf::Mesh& mesh) const {
    std::vector<Primitive> primitives;
    for (const tinygltf::Primitive& prim : mesh.primitives) {
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;  // points/lines are not touchable
      const auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) fail(m_source, ": mesh '", mesh.name, "' has a primitive without POSITION");
      Mesh out;
      {  // the floats go as soon as they are vertices: peak memory of a large mesh
        const std::vector<float> p = m_read.floats(pos->second, 3, "POSITION");
        out.vertices.resize(p.size() / 3);
        for (std::size_t i = 0; i < out.vertices.size(); ++i) out.vertices[i].position = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
      }
      if (auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end()) {
        const std::vector<float> uv = m_read.floats(it->second, 2, "TEXCOORD_0");
        if (uv.size() / 2 != out.vertices.size()) fail(m_source, ": TEXCOORD_0 count differs from POSITION");
        // glTF's UV origin is the image's top-left; ours is bottom-left (see mesh.hpp).
        for (std::size_t i = 0; i < out.vertices.size(); ++i) out.vertices[i].uv = {uv[2 * i], 1.0f - uv[2 * i + 1]};
      }
      if (prim.indices >= 0) {
        out.indices = m_read.indices(prim.indices, out.vertices.size());
      } else {
        for (std::uint32_t i = 0; i < out.vertices.size(); ++i) out.indices.push_back(i);
      }
      out.indices.resize(out.indices.size() / 3 * 3);
      if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
        const std::vector<float> n = m_read.floats(it->second, 3, "NORMAL");
        if (n.size() != 3 * out.vertices.size()) fail(m_source, ": NORMAL count differs from POSITION");
        for (std::size_t i = 0; i < out.vertices.size(); ++i) out.vertices[i].normal = {n[3 * i], n[3 * i + 1], n[3 * i + 2]};
      } else {
        computeNormals(out);
      }
      primitives.push_back({std::move(out), prim.material});
    }
    return primitives;
  }

  // One scene material per (glTF material, MPEG haptic material) pair: the haptic material hangs
  // off the mesh, so one glTF material may feel different on two meshes.
  int material(int gltfIndex, int haptic) {
    if (auto it = m_materials.find({gltfIndex, haptic}); it != m_materials.end()) return it->second;
    Material out;
    if (gltfIndex >= 0) {
      const tinygltf::Material& mat = m_read.element(m_model.materials, gltfIndex, "material");
      out.name = mat.name;
      const auto& f = mat.pbrMetallicRoughness.baseColorFactor;
      if (f.size() == 4) out.baseColor = {float(f[0]), float(f[1]), float(f[2]), float(f[3])};
      if (mat.pbrMetallicRoughness.baseColorTexture.index >= 0) {
        out.albedoTexture = texture(mat.pbrMetallicRoughness.baseColorTexture.index);
      }
      readTactileExtras(mat, out);
    } else {
      out.name = "default";
    }
    if (haptic >= 0) gltf::applyHapticMaterial(m_model, haptic, m_source, out, m_scene);
    m_scene.materials.push_back(std::move(out));
    return m_materials[{gltfIndex, haptic}] = int(m_scene.materials.size()) - 1;
  }

  void readTactileExtras(const tinygltf::Material& mat, Material& out) {
    if (!mat.extras.IsObject() || !mat.extras.Has("vtouching")) return;
    const tinygltf::Value& t = mat.extras.Get("vtouching");
    const std::string where = m_source + ": material '" + mat.name + "' extras.vtouching";
    if (!t.IsObject()) fail(where, " must be an object");
    if (t.Has("vibration_map")) {
      if (!t.Get("vibration_map").IsString()) fail(where, ".vibration_map must be a file name");
      const std::filesystem::path map = m_baseDir / t.Get("vibration_map").Get<std::string>();
      if (!m_options.allowOutsideFolder) checkInsideFolder(map, m_baseDir, where + ".vibration_map");
      m_scene.vibrationMaps.push_back(loadChannelAsFloat(map, 0));
      out.vibrationMap = int(m_scene.vibrationMaps.size()) - 1;
    }
    gltf::readTactileSettings(t, where, out);
  }

  int texture(int gltfTexture) {
    const tinygltf::Texture& tex = m_read.element(m_model.textures, gltfTexture, "texture");
    if (auto it = m_textures.find(tex.source); it != m_textures.end()) return it->second;
    const tinygltf::Image& img = m_read.element(m_model.images, tex.source, "image");
    if (img.width <= 0 || img.height <= 0 || img.image.empty()) fail(m_source, ": image '", img.uri, "' has no pixels");
    const int bytesPerComponent = img.bits == 16 ? 2 : 1;
    if (img.component < 1 || img.component > 4 ||
        img.image.size() < std::size_t(img.width) * std::size_t(img.height) * std::size_t(img.component * bytesPerComponent)) {
      fail(m_source, ": image '", img.uri, "' has inconsistent pixel data");
    }
    Image8 rgba(img.width, img.height, 4);
    for (std::size_t i = 0; i < std::size_t(img.width) * std::size_t(img.height); ++i) {
      for (int c = 0; c < 4; ++c) {
        const int from = img.component >= 3 ? c : (c < 3 ? 0 : 1);
        const bool present = c < 3 || img.component == 4 || img.component == 2;
        // 16-bit images keep their high (little-endian second) byte.
        const std::size_t offset = (i * std::size_t(img.component) + std::size_t(from)) * std::size_t(bytesPerComponent);
        rgba.pixels[i * 4 + std::size_t(c)] = present ? img.image[offset + std::size_t(bytesPerComponent - 1)] : 255;
      }
    }
    m_scene.textures.push_back(std::move(rgba));
    return m_textures[tex.source] = int(m_scene.textures.size()) - 1;
  }

  const tinygltf::Model& m_model;
  std::string m_source;
  gltf::AccessorReader m_read;
  std::filesystem::path m_baseDir;
  GltfLoadOptions m_options;
  std::uint64_t m_visits = 0;
  std::vector<Instance> m_instances;  // at most budget::kSceneNodeVisits
  Scene m_scene;
  std::map<std::pair<int, int>, int> m_materials;
  std::map<int, int> m_textures;
};

}  // namespace

void checkInsideFolder(const std::filesystem::path& path, const std::filesystem::path& folder, const std::string& what) {
  std::error_code ec;
  const std::filesystem::path root = std::filesystem::weakly_canonical(folder.empty() ? "." : folder, ec);
  const std::filesystem::path resolved = std::filesystem::weakly_canonical(path, ec);
  if (ec) return;  // unresolvable (a loop, no permission): the read that follows names the problem
  auto r = root.begin(), p = resolved.begin();
  for (; r != root.end() && p != resolved.end() && *r == *p; ++r, ++p) {}
  if (r != root.end() && !(std::next(r) == root.end() && r->empty())) {
    fail(what, " '", path.string(), "' is outside the scene folder '", root.string(),
         "' (pass --allow-outside-paths to allow it)");
  }
}

Scene loadGltfScene(const std::filesystem::path& path, const GltfLoadOptions& options) {
  const std::string source = "glTF '" + path.string() + "'";
  const LoadScope loading(source);
  const std::filesystem::path baseDir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  const tinygltf::Model model = [&] {  // the file's bytes are freed once parsed
    const std::string bytes = readInputFile(path, "glTF", budget::kSceneFileBytes);
    return gltf::parseModel(bytes, path.extension() == ".glb", source, baseDir, options);
  }();
  return GltfConverter(model, source, baseDir, options).convert();
}

Scene loadGltfScene(const std::string& bytes, bool binary, const std::string& sourceName,
                    const std::filesystem::path& baseDir, const GltfLoadOptions& options) {
  const LoadScope loading(sourceName);
  const tinygltf::Model model = gltf::parseModel(bytes, binary, sourceName, baseDir, options);
  return GltfConverter(model, sourceName, baseDir, options).convert();
}

}  // namespace vt
