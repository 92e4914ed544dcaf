#pragma once
// Embree 3, the comparison point of the collision figures (vt_bench haptics): a mesh in one
// Embree scene whose device, geometry and buffers are made up front, so that build() times
// the BVH build alone (rtcCommitScene), and its ray, ray-stream and point queries answering
// what ours answer (nearest distance, +inf for none).
#include <embree3/rtcore.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "vt/collision/query.hpp"
#include "vt/collision/triangle.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/mesh.hpp"

namespace vt::bench {

/// No hit: the nearest distance a query reports when it finds nothing.
inline constexpr float kNone = std::numeric_limits<float>::infinity();

/// One Embree scene over a mesh (single-threaded device: it builds and queries on the caller).
class EmbreeMesh {
 public:
  /// Device, scene and geometry with the mesh's positions and indices; nothing built yet.
  /// `isa`: empty for Embree's best kernels for this CPU, or a device `isa=` value ("avx2").
  EmbreeMesh(const Mesh& mesh, RTCBuildQuality quality, const std::string& isa = {})
      : m_device(rtcNewDevice(("threads=1,hugepages=1" + (isa.empty() ? "" : ",isa=" + isa)).c_str())),
        m_indices(mesh.indices) {
    if (!m_device) fail("embree: rtcNewDevice failed (error ", int(rtcGetDeviceError(nullptr)), ")");
    m_scene = rtcNewScene(m_device);
    rtcSetSceneBuildQuality(m_scene, quality);
    RTCGeometry geom = rtcNewGeometry(m_device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geom, quality);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), mesh.vertices.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), mesh.triangleCount()));
    m_positions.reserve(mesh.vertices.size());
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      m_positions.push_back(mesh.vertices[i].position);
      for (int k = 0; k < 3; ++k) vb[3 * i + std::size_t(k)] = mesh.vertices[i].position[k];
    }
    for (std::size_t i = 0; i < mesh.indices.size(); ++i) ib[i] = mesh.indices[i];
    rtcCommitGeometry(geom);
    rtcAttachGeometry(m_scene, geom);
    rtcReleaseGeometry(geom);
    rtcInitIntersectContext(&m_context);
  }
  ~EmbreeMesh() {
    rtcReleaseScene(m_scene);
    rtcReleaseDevice(m_device);
  }
  EmbreeMesh(const EmbreeMesh&) = delete;
  EmbreeMesh& operator=(const EmbreeMesh&) = delete;

  /// The BVH build: all that the build figures time.
  void build() { rtcCommitScene(m_scene); }

  /// Nearest hit distance along the ray (rtcIntersect1), or kNone.
  float intersect(const collision::Ray& r) const {
    RTCRayHit rh = rayHit(r);
    rtcIntersect1(m_scene, &m_context, &rh);
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh.ray.tfar : kNone;
  }

  /// intersect() for up to 16 rays in one ray-stream call (rtcIntersect1M).
  void intersect16(const collision::Ray* rays, std::size_t count, float* t) const {
    RTCRayHit rh[16];
    for (std::size_t k = 0; k < count; ++k) rh[k] = rayHit(rays[k]);
    rtcIntersect1M(m_scene, &m_context, rh, unsigned(count), sizeof(RTCRayHit));
    for (std::size_t k = 0; k < count; ++k) t[k] = rh[k].hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh[k].ray.tfar : kNone;
  }

  /// Distance from the sphere's centre to the nearest surface point within its radius
  /// (rtcPointQuery; the callback tests triangles as ours do and shrinks the radius), or kNone.
  float closestDistance(const collision::Sphere& s) const {
    RTCPointQuery query{};
    query.x = s.center.x, query.y = s.center.y, query.z = s.center.z;
    query.radius = s.radius_m;
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    PointQueryState state{this, s.radius_m * s.radius_m, false};
    rtcPointQuery(m_scene, &query, &context, &closestPointCallback, &state);
    return state.found ? std::sqrt(state.bestD2) : kNone;
  }

 private:
  struct PointQueryState {
    const EmbreeMesh* mesh;
    float bestD2;
    bool found;
  };

  static RTCRayHit rayHit(const collision::Ray& r) {
    RTCRayHit rh{};
    rh.ray.org_x = r.origin.x, rh.ray.org_y = r.origin.y, rh.ray.org_z = r.origin.z;
    rh.ray.dir_x = r.direction.x, rh.ray.dir_y = r.direction.y, rh.ray.dir_z = r.direction.z;
    rh.ray.tnear = r.tMin;
    rh.ray.tfar = r.tMax;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    return rh;
  }

  static bool closestPointCallback(RTCPointQueryFunctionArguments* args) {
    auto* state = static_cast<PointQueryState*>(args->userPtr);
    const EmbreeMesh& m = *state->mesh;
    const std::size_t base = std::size_t(args->primID) * 3;
    const glm::vec3 p(args->query->x, args->query->y, args->query->z);
    float u, v;
    const glm::vec3 q = collision::closestPointOnTriangle(p, m.m_positions[m.m_indices[base]],
                                                          m.m_positions[m.m_indices[base + 1]],
                                                          m.m_positions[m.m_indices[base + 2]], u, v);
    const float d2 = glm::dot(q - p, q - p);
    if (!(d2 < state->bestD2)) return false;
    state->bestD2 = d2;
    state->found = true;
    args->query->radius = std::sqrt(d2);  // shrink the search as our own query does
    return true;
  }

  RTCDevice m_device = nullptr;
  RTCScene m_scene = nullptr;
  mutable RTCIntersectContext m_context{};
  std::vector<glm::vec3> m_positions;
  std::vector<std::uint32_t> m_indices;
};

}  // namespace vt::bench
