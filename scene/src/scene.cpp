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

}  // namespace vt
