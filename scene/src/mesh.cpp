#include "vt/scene/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vt {

Aabb bounds(const Mesh& mesh) noexcept {
  if (mesh.vertices.empty()) return {};
  Aabb box{mesh.vertices[0].position, mesh.vertices[0].position};
  for (const Vertex& v : mesh.vertices) {
    box.min = glm::min(box.min, v.position);
    box.max = glm::max(box.max, v.position);
  }
  return box;
}

void computeNormals(Mesh& mesh) noexcept {
  // Edges in double, divided by the largest coordinate: a cross product of coordinates near a
  // float's limits (a file may hold them) neither overflows to a NaN normal nor underflows, and
  // every triangle keeps its direction and its weight relative to the others.
  double largest = 0.0;
  for (Vertex& v : mesh.vertices) {
    v.normal = glm::vec3(0.0f);
    for (int k = 0; k < 3; ++k) largest = std::max(largest, std::abs(double(v.position[k])));
  }
  const double scale = largest > 0.0 && std::isfinite(largest) ? 1.0 / largest : 0.0;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    Vertex& a = mesh.vertices[mesh.indices[t]];
    Vertex& b = mesh.vertices[mesh.indices[t + 1]];
    Vertex& c = mesh.vertices[mesh.indices[t + 2]];
    const glm::dvec3 origin(a.position);
    const glm::vec3 n(glm::cross((glm::dvec3(b.position) - origin) * scale, (glm::dvec3(c.position) - origin) * scale));
    a.normal += n;
    b.normal += n;
    c.normal += n;
  }
  for (Vertex& v : mesh.vertices) {
    const float len = glm::length(v.normal);
    v.normal = len > 0.0f ? v.normal / len : glm::vec3(0, 1, 0);
  }
}

namespace {

// Appends one quad (two triangles) with corners a,b,c,d counter-clockwise seen from outside.
void addQuad(Mesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 normal) {
  const auto base = std::uint32_t(mesh.vertices.size());
  mesh.vertices.push_back({a, normal, {0.0f, 0.0f}});
  mesh.vertices.push_back({b, normal, {1.0f, 0.0f}});
  mesh.vertices.push_back({c, normal, {1.0f, 1.0f}});
  mesh.vertices.push_back({d, normal, {0.0f, 1.0f}});
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

}  // namespace

Mesh makeBox(glm::vec3 size_m) {
  const glm::vec3 h = size_m * 0.5f;
  Mesh mesh;
  // Top (+Y): v grows toward -Z, so the image's top row lies along the far edge.
  addQuad(mesh, {-h.x, h.y, h.z}, {h.x, h.y, h.z}, {h.x, h.y, -h.z}, {-h.x, h.y, -h.z}, {0, 1, 0});
  addQuad(mesh, {-h.x, -h.y, -h.z}, {h.x, -h.y, -h.z}, {h.x, -h.y, h.z}, {-h.x, -h.y, h.z}, {0, -1, 0});
  addQuad(mesh, {-h.x, -h.y, h.z}, {h.x, -h.y, h.z}, {h.x, h.y, h.z}, {-h.x, h.y, h.z}, {0, 0, 1});
  addQuad(mesh, {h.x, -h.y, -h.z}, {-h.x, -h.y, -h.z}, {-h.x, h.y, -h.z}, {h.x, h.y, -h.z}, {0, 0, -1});
  addQuad(mesh, {h.x, -h.y, h.z}, {h.x, -h.y, -h.z}, {h.x, h.y, -h.z}, {h.x, h.y, h.z}, {1, 0, 0});
  addQuad(mesh, {-h.x, -h.y, -h.z}, {-h.x, -h.y, h.z}, {-h.x, h.y, h.z}, {-h.x, h.y, -h.z}, {-1, 0, 0});
  return mesh;
}

Mesh makePlane(glm::vec2 size_m, int divisions) {
  divisions = std::max(divisions, 1);
  Mesh mesh;
  const int n = divisions + 1;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const float u = float(i) / float(divisions);
      const float v = float(j) / float(divisions);
      // v = 0 at the far edge (-Z), matching the box's top face.
      mesh.vertices.push_back({{(u - 0.5f) * size_m.x, 0.0f, (v - 0.5f) * size_m.y}, {0, 1, 0}, {u, 1.0f - v}});
    }
  }
  for (int j = 0; j < divisions; ++j) {
    for (int i = 0; i < divisions; ++i) {
      const auto a = std::uint32_t(j * n + i), b = a + 1, c = a + std::uint32_t(n) + 1, d = a + std::uint32_t(n);
      mesh.indices.insert(mesh.indices.end(), {a, d, c, a, c, b});
    }
  }
  return mesh;
}

Mesh makeSphere(int slices, int stacks) {
  Mesh mesh;
  for (int j = 0; j <= stacks; ++j) {
    const float phi = std::numbers::pi_v<float> * float(j) / float(stacks);
    for (int i = 0; i <= slices; ++i) {
      const float theta = 2.0f * std::numbers::pi_v<float> * float(i) / float(slices);
      const glm::vec3 n{std::sin(phi) * std::cos(theta), std::cos(phi), std::sin(phi) * std::sin(theta)};
      mesh.vertices.push_back({n, n, {float(i) / float(slices), float(j) / float(stacks)}});
    }
  }
  for (int j = 0; j < stacks; ++j) {
    for (int i = 0; i < slices; ++i) {
      const auto a = std::uint32_t(j * (slices + 1) + i), b = a + 1;
      const auto c = a + std::uint32_t(slices + 1), d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
  }
  return mesh;
}

Mesh makeCapsule(int slices, int capStacks) {
  // A sphere whose upper half is lifted by 1: the triangles spanning the equator stretch into
  // the cylinder, so the surface stays closed with no extra band.
  Mesh mesh = makeSphere(slices, capStacks * 2);
  for (Vertex& v : mesh.vertices) {
    if (v.uv.y < 0.5f) v.position.y += 1.0f;
  }
  return mesh;
}

}  // namespace vt
