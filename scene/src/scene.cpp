#include "vt/scene/scene.hpp"

#include "vt/core/error.hpp"

namespace vt {

void Scene::validate() const {
  auto inRange = [](int index, std::size_t size) { return index >= 0 && std::size_t(index) < size; };
  for (const Material& m : materials) {
    if (m.albedoTexture != -1 && !inRange(m.albedoTexture, textures.size())) {
      fail("scene: material '", m.name, "' references texture ", m.albedoTexture, " of ", textures.size());
    }
    if (m.vibrationMap != -1 && !inRange(m.vibrationMap, vibrationMaps.size())) {
      fail("scene: material '", m.name, "' references vibration map ", m.vibrationMap, " of ",
           vibrationMaps.size());
    }
    if (m.vibrationMapAcross != -1 && !inRange(m.vibrationMapAcross, vibrationMaps.size())) {
      fail("scene: material '", m.name, "' references across vibration map ", m.vibrationMapAcross, " of ",
           vibrationMaps.size());
    }
  }
  for (const SceneObject& o : objects) {
    if (!inRange(o.mesh, meshes.size())) fail("scene: object '", o.name, "' references mesh ", o.mesh);
    if (!inRange(o.material, materials.size())) {
      fail("scene: object '", o.name, "' references material ", o.material);
    }
  }
  for (const Image8& t : textures) {
    if (t.channels != 4) fail("scene: textures must be RGBA8 (got ", t.channels, " channels)");
  }
}

namespace {

// FNV-1a over raw bytes: stable across runs and machines of the same endianness (all ours).
class Fnv1a {
 public:
  void bytes(const void* data, std::size_t size) noexcept {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) m_hash = (m_hash ^ p[i]) * 0x100000001b3ull;
  }
  template <class T>
  void value(const T& v) noexcept {
    bytes(&v, sizeof v);
  }
  void text(const std::string& s) noexcept {
    value(s.size());
    bytes(s.data(), s.size());
  }
  std::uint64_t hash() const noexcept { return m_hash; }

 private:
  std::uint64_t m_hash = 0xcbf29ce484222325ull;
};

}  // namespace

std::uint64_t tactileDigest(const Scene& scene) noexcept {
  Fnv1a h;
  h.value(scene.objects.size());
  for (const SceneObject& o : scene.objects) {
    h.text(o.name);
    h.value(o.mesh), h.value(o.material), h.value(o.T_world_object);
  }
  h.value(scene.meshes.size());
  for (const Mesh& m : scene.meshes) {
    h.value(m.vertices.size());
    for (const Vertex& v : m.vertices) h.value(v.position), h.value(v.uv);
    h.value(m.indices.size());
    h.bytes(m.indices.data(), m.indices.size() * sizeof(std::uint32_t));
  }
  h.value(scene.materials.size());
  for (const Material& m : scene.materials) {
    h.value(m.vibrationMap), h.value(m.tactileGain), h.value(m.uvTransform), h.value(m.wrapUv);
    h.value(m.physicalWidth_m), h.value(m.vibrationMapAcross), h.value(m.scanDirectionUv);
  }
  h.value(scene.vibrationMaps.size());
  for (const ImageF& map : scene.vibrationMaps) {
    h.value(map.width), h.value(map.height), h.value(map.channels);
    h.bytes(map.pixels.data(), map.pixels.size() * sizeof(float));
  }
  return h.hash();
}

}  // namespace vt
