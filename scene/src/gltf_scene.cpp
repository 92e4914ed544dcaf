#include <cmath>
#include <cstring>
#include <functional>
#include <map>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "gltf_haptic_material.hpp"
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
      : m_model(model), m_source(std::move(source)), m_baseDir(std::move(baseDir)), m_options(options) {}

  Scene convert() {
    if (m_model.scenes.empty()) fail(m_source, ": the file has no scene");
    const int sceneIndex = m_model.defaultScene >= 0 ? m_model.defaultScene : 0;
    if (std::size_t(sceneIndex) >= m_model.scenes.size()) fail(m_source, ": default scene ", sceneIndex, " missing");
    for (int node : m_model.scenes[std::size_t(sceneIndex)].nodes) visit(node, glm::mat4(1.0f), 0);
    // Each glTF mesh is read once; its instances are copied only after the whole scene's
    // instanced geometry is known to fit the budget (a small file can list one mesh many times).
    std::map<int, std::vector<Primitive>> meshes;
    std::uint64_t vertices = 0, indices = 0;
    for (const Instance& instance : m_instances) {
      auto [it, isNew] = meshes.try_emplace(instance.mesh);
      if (isNew) it->second = readMesh(m_model.meshes[std::size_t(instance.mesh)]);
      for (const Primitive& p : it->second) vertices += p.mesh.vertices.size(), indices += p.mesh.indices.size();
      const bool tooMany = vertices > budget::kSceneVertices;
      if (tooMany || indices > budget::kSceneIndices) {
        fail(m_source, ": the scene's ", m_instances.size(), " mesh instances hold more than ",
             tooMany ? budget::kSceneVertices : budget::kSceneIndices, tooMany ? " vertices" : " indices",
             " (one mesh used by many nodes?)");
      }
    }
    for (const Instance& instance : m_instances) {
      const tinygltf::Mesh& mesh = m_model.meshes[std::size_t(instance.mesh)];
      const int haptic = gltf::hapticMaterialIndex(m_model, mesh, m_source);
      for (const Primitive& p : meshes[instance.mesh]) {
        m_scene.meshes.push_back(p.mesh);
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

  template <class T>
  const T& element(const std::vector<T>& items, int index, const char* what) const {
    if (index < 0 || std::size_t(index) >= items.size()) fail(m_source, ": ", what, " index ", index, " out of range");
    return items[std::size_t(index)];
  }

  void visit(int nodeIndex, const glm::mat4& T_world_parent, int depth) {
    if (depth > 64) fail(m_source, ": node hierarchy deeper than 64 (a cycle?)");
    // Depth alone does not bound the work: a node listing its child twice doubles it per level.
    if (++m_visits > budget::kSceneNodeVisits) {
      fail(m_source, ": more than ", budget::kSceneNodeVisits, " node visits (nodes listed as children many times?)");
    }
    const tinygltf::Node& node = element(m_model.nodes, nodeIndex, "node");
    glm::mat4 local(1.0f);
    if (node.matrix.size() == 16) {
      for (int i = 0; i < 16; ++i) glm::value_ptr(local)[i] = float(node.matrix[std::size_t(i)]);
    } else {
      if (node.translation.size() == 3) {
        local = glm::translate(local, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
      }
      if (node.rotation.size() == 4) {
        local *= glm::mat4_cast(glm::quat(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]),
                                          float(node.rotation[2])));
      }
      if (node.scale.size() == 3) local = glm::scale(local, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
    }
    const glm::mat4 T_world_node = T_world_parent * local;
    for (int i = 0; i < 16; ++i) {
      if (!std::isfinite(glm::value_ptr(T_world_node)[i])) {
        fail(m_source, ": node ", nodeIndex, " has a NaN or infinite transform");
      }
    }
    if (node.mesh >= 0) {
      element(m_model.meshes, node.mesh, "mesh");
      m_instances.push_back({node.mesh, node.name, T_world_node});
    }
    for (int child : node.children) visit(child, T_world_node, depth + 1);
  }

  // Copies `count` elements of `components` floats from an accessor, checking every bound.
  std::vector<float> readFloats(int accessorIndex, int components, const char* what) const {
    const tinygltf::Accessor& acc = element(m_model.accessors, accessorIndex, "accessor");
    if (acc.sparse.isSparse) fail(m_source, ": ", what, " uses a sparse accessor (not supported)");
    if (tinygltf::GetNumComponentsInType(std::uint32_t(acc.type)) != components) {
      fail(m_source, ": ", what, " accessor has ", tinygltf::GetNumComponentsInType(std::uint32_t(acc.type)),
           " components, expected ", components);
    }
    const int componentSize = tinygltf::GetComponentSizeInBytes(std::uint32_t(acc.componentType));
    const bool isFloat = acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
    const bool isNormalised = acc.normalized && (acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                                 acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    if (!isFloat && !isNormalised) fail(m_source, ": ", what, " must be float or normalised unsigned data");
    const auto [data, stride] = view(acc, std::size_t(componentSize * components), what);
    std::vector<float> out(acc.count * std::size_t(components));
    for (std::size_t i = 0; i < acc.count; ++i) {
      for (int c = 0; c < components; ++c) {
        const std::uint8_t* p = data + i * stride + std::size_t(c * componentSize);
        float v = 0.0f;
        if (isFloat) std::memcpy(&v, p, 4);
        else if (componentSize == 1) v = float(*p) / 255.0f;
        else {
          std::uint16_t u = 0;
          std::memcpy(&u, p, 2);
          v = float(u) / 65535.0f;
        }
        if (!std::isfinite(v)) fail(m_source, ": ", what, " element ", i, " is NaN or infinite");
        out[i * std::size_t(components) + std::size_t(c)] = v;
      }
    }
    return out;
  }

  std::vector<std::uint32_t> readIndices(int accessorIndex, std::size_t vertexCount) const {
    const tinygltf::Accessor& acc = element(m_model.accessors, accessorIndex, "accessor");
    if (acc.sparse.isSparse || acc.type != TINYGLTF_TYPE_SCALAR) fail(m_source, ": indices must be scalars");
    const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(acc.componentType));
    if (size != 1 && size != 2 && size != 4) fail(m_source, ": indices have an invalid component type");
    const auto [data, stride] = view(acc, std::size_t(size), "indices");
    std::vector<std::uint32_t> out(acc.count);
    for (std::size_t i = 0; i < acc.count; ++i) {
      std::uint32_t v = 0;
      std::memcpy(&v, data + i * stride, std::size_t(size));  // little-endian host
      if (v >= vertexCount) fail(m_source, ": index ", v, " out of range (", vertexCount, " vertices)");
      out[i] = v;
    }
    return out;
  }

  std::pair<const std::uint8_t*, std::size_t> view(const tinygltf::Accessor& acc, std::size_t elementSize,
                                                   const char* what) const {
    const tinygltf::BufferView& bv = element(m_model.bufferViews, acc.bufferView, "bufferView");
    const tinygltf::Buffer& buffer = element(m_model.buffers, bv.buffer, "buffer");
    const std::size_t stride = bv.byteStride ? bv.byteStride : elementSize;
    // Every bound without a product or sum that can wrap: counts near 2^64 come from files too.
    const bool viewFits = bv.byteOffset <= buffer.data.size() && bv.byteLength <= buffer.data.size() - bv.byteOffset;
    const bool firstFits = acc.byteOffset <= bv.byteLength && elementSize <= bv.byteLength - acc.byteOffset;
    const bool countFits =
        acc.count == 0 || (firstFits && acc.count - 1 <= (bv.byteLength - acc.byteOffset - elementSize) / stride);
    if (stride < elementSize || !viewFits || !countFits) {
      fail(m_source, ": ", what, " accessor (count ", acc.count, ") reads past the end of its buffer");
    }
    return {buffer.data.data() + bv.byteOffset + acc.byteOffset, stride};
  }

  std::vector<Primitive> readMesh(const tinygltf::Mesh& mesh) const {
    std::vector<Primitive> primitives;
    for (const tinygltf::Primitive& prim : mesh.primitives) {
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;  // points/lines are not touchable
      const auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) fail(m_source, ": mesh '", mesh.name, "' has a primitive without POSITION");
      Mesh out;
      const std::vector<float> p = readFloats(pos->second, 3, "POSITION");
      out.vertices.resize(p.size() / 3);
      for (std::size_t i = 0; i < out.vertices.size(); ++i) out.vertices[i].position = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
      if (auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end()) {
        const std::vector<float> uv = readFloats(it->second, 2, "TEXCOORD_0");
        if (uv.size() / 2 != out.vertices.size()) fail(m_source, ": TEXCOORD_0 count differs from POSITION");
        // glTF's UV origin is the image's top-left; ours is bottom-left (see mesh.hpp).
        for (std::size_t i = 0; i < out.vertices.size(); ++i) out.vertices[i].uv = {uv[2 * i], 1.0f - uv[2 * i + 1]};
      }
      if (prim.indices >= 0) {
        out.indices = readIndices(prim.indices, out.vertices.size());
      } else {
        for (std::uint32_t i = 0; i < out.vertices.size(); ++i) out.indices.push_back(i);
      }
      out.indices.resize(out.indices.size() / 3 * 3);
      if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
        const std::vector<float> n = readFloats(it->second, 3, "NORMAL");
        if (n.size() != p.size()) fail(m_source, ": NORMAL count differs from POSITION");
        for (std::size_t i = 0; i < out.vertices.size(); ++i) out.vertices[i].normal = {n[3 * i], n[3 * i + 1], n[3 * i + 2]};
      } else {
        computeNormals(out);
      }
      primitives.push_back({std::move(out), prim.material});
    }
    return primitives;
  }

  static void computeNormals(Mesh& mesh) {
    for (Vertex& v : mesh.vertices) v.normal = glm::vec3(0.0f);
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      Vertex& a = mesh.vertices[mesh.indices[t]];
      Vertex& b = mesh.vertices[mesh.indices[t + 1]];
      Vertex& c = mesh.vertices[mesh.indices[t + 2]];
      const glm::vec3 n = glm::cross(b.position - a.position, c.position - a.position);
      a.normal += n;
      b.normal += n;
      c.normal += n;
    }
    for (Vertex& v : mesh.vertices) {
      const float len = glm::length(v.normal);
      v.normal = len > 0.0f ? v.normal / len : glm::vec3(0, 1, 0);
    }
  }

  // One scene material per (glTF material, MPEG haptic material) pair: the haptic material hangs
  // off the mesh, so one glTF material may feel different on two meshes.
  int material(int gltfIndex, int haptic) {
    if (auto it = m_materials.find({gltfIndex, haptic}); it != m_materials.end()) return it->second;
    Material out;
    if (gltfIndex >= 0) {
      const tinygltf::Material& mat = element(m_model.materials, gltfIndex, "material");
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
    const tinygltf::Texture& tex = element(m_model.textures, gltfTexture, "texture");
    if (auto it = m_textures.find(tex.source); it != m_textures.end()) return it->second;
    const tinygltf::Image& img = element(m_model.images, tex.source, "image");
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
  std::filesystem::path m_baseDir;
  GltfLoadOptions m_options;
  std::uint64_t m_visits = 0;
  std::vector<Instance> m_instances;  // at most budget::kSceneNodeVisits
  Scene m_scene;
  std::map<std::pair<int, int>, int> m_materials;
  std::map<int, int> m_textures;
};

// tinygltf's file access, confined to the scene's folder and held to the file budget; the first
// refusal is kept so the error says it in our words.
struct FileAccess {
  std::filesystem::path baseDir;
  GltfLoadOptions options;
  std::string refusal;
};

// Confinement is checked before existence: a URI outside the folder is refused in our words
// whether or not its target exists (tinygltf would otherwise say "File not found").
bool confined(FileAccess& access, const std::string& path) {
  if (access.options.allowOutsideFolder) return true;
  try {
    checkInsideFolder(path, access.baseDir, "URI");
    return true;
  } catch (const Error& e) {
    if (access.refusal.empty()) access.refusal = e.what();
    return false;
  }
}

bool fileExists(const std::string& path, void* user) {
  if (!confined(*static_cast<FileAccess*>(user), path)) return false;
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

std::string expandPath(const std::string& path, void*) { return path; }  // no ~ or $VAR expansion

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto& access = *static_cast<FileAccess*>(user);
  if (!confined(access, path)) {
    if (err) *err = access.refusal;
    return false;
  }
  try {
    const std::string bytes = readInputFile(path, "glTF resource", budget::kSceneFileBytes);
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const Error& e) {
    if (access.refusal.empty()) access.refusal = e.what();
    if (err) *err = e.what();
    return false;
  }
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "writing is not supported";
  return false;
}

// Textures decode through our PNG/JPEG path: the same size budget and chunk checks as every image.
// Like tinygltf's own loader, 16-bit PNGs stay 16-bit (vibration maps are exported that way).
bool decodeImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                 const unsigned char* bytes, int size, void*) {
  try {
    const std::span<const std::uint8_t> encoded(bytes, std::size_t(size));
    const std::string source = str("image[", index, "] '", image->name, "'");
    image->component = 4;
    if (is16BitImage(encoded)) {
      const Image16 rgba = loadImage16(encoded, source, 4);
      image->width = rgba.width;
      image->height = rgba.height;
      image->bits = 16;
      image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
      image->image.resize(rgba.pixels.size() * sizeof(std::uint16_t));  // host order, as tinygltf
      std::memcpy(image->image.data(), rgba.pixels.data(), image->image.size());
    } else {
      Image8 rgba = loadImage8(encoded, source, 4);
      image->width = rgba.width;
      image->height = rgba.height;
      image->bits = 8;
      image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
      image->image = std::move(rgba.pixels);
    }
    return true;
  } catch (const Error& e) {
    if (err) *err += e.what();
    return false;
  }
}

// tinygltf ends each of its messages with a newline; ours are one line.
std::string oneLine(std::string text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at)) text.replace(at, 1, "; ");
  return text;
}

Scene loadFromBytes(const std::string& bytes, bool binary, const std::string& source,
                    const std::filesystem::path& baseDir, const GltfLoadOptions& options) {
  if (bytes.size() > budget::kSceneFileBytes) fail(source, ": larger than ", budget::kSceneFileBytes, " bytes");
  tinygltf::TinyGLTF loader;
  FileAccess access{baseDir, options, {}};
  loader.SetFsCallbacks({&fileExists, &expandPath, &readWholeFile, &writeWholeFile, &access});
  loader.SetImageLoader(&decodeImage, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                                       reinterpret_cast<const unsigned char*>(bytes.data()),
                                                       unsigned(bytes.size()), baseDir.string())
                         : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), unsigned(bytes.size()),
                                                      baseDir.string());
  // tinygltf only warns about an image it could not read; a refused file is an error either way.
  if (!access.refusal.empty()) fail(source, ": ", access.refusal);
  if (!ok) fail(source, ": not a valid glTF file (", err.empty() ? "parse error" : oneLine(err), ")");
  return GltfConverter(model, source, baseDir, options).convert();
}

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
  const std::string bytes = readInputFile(path, "glTF", budget::kSceneFileBytes);
  const std::filesystem::path baseDir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  return loadFromBytes(bytes, path.extension() == ".glb", source, baseDir, options);
}

Scene loadGltfScene(const std::string& bytes, bool binary, const std::string& sourceName,
                    const std::filesystem::path& baseDir, const GltfLoadOptions& options) {
  return loadFromBytes(bytes, binary, sourceName, baseDir, options);
}

}  // namespace vt
