#pragma once
// Triangle meshes: the one geometry type shared by rendering and collision.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace vt {

struct Vertex {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  glm::vec2 uv{0.0f};
};

/// Indexed triangle list, positions in metres in the mesh's own frame.
struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;  // 3 per triangle

  std::size_t triangleCount() const noexcept { return indices.size() / 3; }
};

struct Aabb {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};
};

/// Bounds of all vertices (zero box for an empty mesh).
Aabb bounds(const Mesh& mesh) noexcept;

/// A box centred on the origin; UV (0,0)..(1,1) on every face, top face (+Y) UV with
/// u along +X and v along -Z so a texture reads upright when seen from above the front.
Mesh makeBox(glm::vec3 size_m);

/// A flat rectangle in the XZ plane facing +Y, `divisions` quads per side.
Mesh makePlane(glm::vec2 size_m, int divisions = 1);

/// A UV sphere of unit radius (used instanced for hand joints).
Mesh makeSphere(int slices = 16, int stacks = 8);

/// A capsule segment of unit radius from y=0 to y=1, hemispherical caps (instanced bones).
Mesh makeCapsule(int slices = 12, int capStacks = 4);

}  // namespace vt
