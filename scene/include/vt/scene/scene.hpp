#pragma once
// The scene description shared by renderer, collision and haptics: plain data, no GPU or
// device types. Built once, then shared read-only (std::shared_ptr<const Scene>); an edit
// publishes a new Scene.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "vt/scene/camera.hpp"
#include "vt/scene/image.hpp"
#include "vt/scene/mesh.hpp"

namespace vt {

/// How a surface looks and feels.
struct Material {
  std::string name;
  glm::vec4 baseColor{1.0f};          // multiplies the albedo texture (linear RGB)
  int albedoTexture = -1;             // index into Scene::textures (sRGB RGBA8), -1 = none
  int vibrationMap = -1;              // index into Scene::vibrationMaps, -1 = not tactile
  float tactileGain = 0.5f;           // the paper's default gain
  glm::mat3 uvTransform{1.0f};        // applied to mesh UVs before any texture lookup
  bool wrapUv = false;                // repeat (true) or clamp (false) outside [0,1]
  float physicalWidth_m = 0.0f;       // size the map covers along u (0 = unknown)
  int vibrationMapAcross = -1;        // map scanned across vibrationMap's direction, -1 = none
  glm::vec2 scanDirectionUv{1.0f, 0.0f};  // unit UV direction (in map pixels) vibrationMap was scanned along
};

/// One placed mesh.
struct SceneObject {
  std::string name;
  int mesh = -1;
  int material = -1;
  glm::mat4 T_world_object{1.0f};
};

struct Scene {
  std::vector<Mesh> meshes;
  std::vector<Image8> textures;       // RGBA8, sRGB-encoded colour
  std::vector<ImageF> vibrationMaps;  // one channel, [0,1], row 0 = top of the image (v = 1)
  std::vector<Material> materials;
  std::vector<SceneObject> objects;
  OrbitCamera camera;
  glm::vec3 lightDirection{-0.4f, -1.0f, -0.3f};  // direction the light travels, world space
  /// How the tactile gains relate across objects, for the HUD and traces: "absolute (...)",
  /// "normalised", "gains FILE"; empty when the source says nothing.
  std::string intensity;
  /// What the loader read but does not render (e.g. glTF stiffness maps), one line each.
  std::vector<std::string> unused;

  /// Throws vt::Error naming the object/material when an index is out of range.
  void validate() const;
};

/// A 64-bit fingerprint of what can be touched: object placement, mesh geometry and UVs,
/// tactile material settings and vibration maps (not colours or textures). Two processes that
/// loaded the same scene description agree on it; the network session compares them.
std::uint64_t tactileDigest(const Scene& scene) noexcept;

}  // namespace vt
