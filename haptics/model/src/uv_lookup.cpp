#include "vt/haptics/uv_lookup.hpp"

#include "vt/core/error.hpp"

namespace vt::haptics {

glm::vec2 interpolateUv(const Mesh& mesh, std::uint32_t triangle, float u, float v) noexcept {
  // Loaders validate indices and the BVH only reports triangles of this mesh: a bad index here
  // is a bug (failing in checked builds, counted in release, where the lookup gives (0, 0)).
  const std::size_t base = std::size_t(triangle) * 3;
  if (!VT_INVARIANT(base + 2 < mesh.indices.size())) return {0.0f, 0.0f};
  const std::uint32_t i0 = mesh.indices[base], i1 = mesh.indices[base + 1], i2 = mesh.indices[base + 2];
  const std::size_t n = mesh.vertices.size();
  if (!VT_INVARIANT(i0 < n && i1 < n && i2 < n)) return {0.0f, 0.0f};
  return (1.0f - u - v) * mesh.vertices[i0].uv + u * mesh.vertices[i1].uv + v * mesh.vertices[i2].uv;
}

}  // namespace vt::haptics
