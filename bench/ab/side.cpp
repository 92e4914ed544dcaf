// One side of the A/B program (scripts/collision-ab.sh): compiled once against revision A's
// collision sources (namespace vt, SIDE=A) and once against revision B's (every `vt` renamed
// `vtb` by the preprocessor, SIDE=B), so both libraries live in one process.
#include <memory>
#include <span>
#include <vector>

#include "ab.hpp"
#include "interleaved_runs.hpp"
#include "vt/collision/collision_scene.hpp"
#include "vt/scene/scene.hpp"

#define VT_AB_CAT2(a, b) a##b
#define VT_AB_CAT(a, b) VT_AB_CAT2(a, b)
#define VT_AB_NAME(x) VT_AB_CAT(x, SIDE)

namespace {

struct Side final : ab::World {
  explicit Side(const ab::Workload& work) : scene(std::make_shared<vt::Scene>()) {
    vt::Mesh mesh;
    mesh.vertices.resize(work.positions.size());
    for (std::size_t i = 0; i < work.positions.size(); ++i) mesh.vertices[i].position = work.positions[i];
    mesh.indices = work.indices;
    scene->meshes.push_back(std::move(mesh));
    scene->materials.emplace_back();
    scene->objects.push_back({"mesh", 0, 0, glm::mat4(1.0f)});
  }

  double rebuild() override {
    world.reset();
    const double t0 = vt::bench::threadCpuSeconds();
    world = std::make_unique<vt::collision::CollisionScene>(scene);
    return vt::bench::threadCpuSeconds() - t0;
  }

  void answer(const ab::Workload& work, float* answers) override {
    using vt::collision::Ray;
    using vt::collision::RayHit;
    const std::size_t n = work.origins.size();
    if (work.kind == ab::Kind::Rays || work.kind == ab::Kind::Build) {
      for (std::size_t i = 0; i < n; ++i) {
        Ray ray;
        ray.origin = work.origins[i];
        ray.direction = work.directions[i];
        const RayHit hit = world->intersect(ray);
        answers[i] = hit.hit() ? hit.t : -1.0f;
      }
    } else if (work.kind == ab::Kind::RayBatches) {
      constexpr std::size_t kBatch = 16;
      Ray rays[kBatch];
      RayHit hits[kBatch];
      for (std::size_t first = 0; first < n; first += kBatch) {
        const std::size_t count = std::min(kBatch, n - first);
        for (std::size_t k = 0; k < count; ++k) rays[k].origin = work.origins[first + k], rays[k].direction = work.directions[first + k];
        world->intersect(std::span<const Ray>(rays, count), std::span<RayHit>(hits, count));
        for (std::size_t k = 0; k < count; ++k) answers[first + k] = hits[k].hit() ? hits[k].t : -1.0f;
      }
    } else if (work.kind == ab::Kind::SphereBatches) {
      constexpr std::size_t kBatch = 12;
      vt::collision::Sphere spheres[kBatch];
      vt::collision::SphereContact contacts[kBatch];
      for (std::size_t first = 0; first < n; first += kBatch) {
        const std::size_t count = std::min(kBatch, n - first);
        for (std::size_t k = 0; k < count; ++k) spheres[k] = {work.origins[first + k], work.radius};
        world->sphereContacts(std::span<const vt::collision::Sphere>(spheres, count),
                              std::span<vt::collision::SphereContact>(contacts, count));
        for (std::size_t k = 0; k < count; ++k) answers[first + k] = contacts[k].hit() ? contacts[k].distance_m : -1.0f;
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        const auto contact = world->sphereContact({work.origins[i], work.radius});
        answers[i] = contact.hit() ? contact.distance_m : -1.0f;
      }
    }
  }

  std::shared_ptr<vt::Scene> scene;
  std::unique_ptr<vt::collision::CollisionScene> world;
};

}  // namespace

std::unique_ptr<ab::World> VT_AB_NAME(makeWorld)(const ab::Workload& work) { return std::make_unique<Side>(work); }
