#pragma once
// Triangle meshes: the one geometry type shared by rendering and collision.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace vt {

/// UV convention (as the paper's Unity app): origin at the image's bottom-left, v up.
/// An image's row r covers v in [1 - (r+1)/h, 1 - r/h]: row = (1 - v) * height, col = u * width.
/// Renderers sample textures at (u, 1 - v); glTF's top-left UVs are flipped on load.
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

/// Smooth vertex normals: the area-weighted mean of the adjacent triangles' normals.
void computeNormals(Mesh& mesh) noexcept;

/// A box centred on the origin; UV (0,0)..(1,1) on every face; on the top face (+Y) u runs
/// along +X and v along -Z, so an image reads upright when seen from the front (+Z).
Mesh makeBox(glm::vec3 size_m);

/// A flat rectangle in the XZ plane facing +Y, `divisions` quads per side.
Mesh makePlane(glm::vec2 size_m, int divisions = 1);

/// A UV sphere of unit radius (used instanced for hand joints).
Mesh makeSphere(int slices = 16, int stacks = 8);

/// A capsule segment of unit radius from y=0 to y=1, hemispherical caps (instanced bones).
Mesh makeCapsule(int slices = 12, int capStacks = 4);

}  // namespace vt
