#pragma once
// From a collision hit (triangle + barycentrics) to the material's texture coordinate.
// Pure functions; any thread (the haptic thread uses them every tick).
#include <cstdint>

#include <glm/glm.hpp>

#include "vt/scene/mesh.hpp"

namespace vt::haptics {

/// Vertex UVs interpolated at barycentrics (u weights vertex 1, v vertex 2). A triangle index
/// out of range gives (0,0).
glm::vec2 interpolateUv(const Mesh& mesh, std::uint32_t triangle, float u, float v) noexcept;

/// Material::uvTransform applied to a UV (homogeneous 2D: uv' = (M * (u, v, 1)).xy).
inline glm::vec2 applyUvTransform(const glm::mat3& uvTransform, glm::vec2 uv) noexcept {
  return glm::vec2(uvTransform * glm::vec3(uv, 1.0f));
}

}  // namespace vt::haptics
