#include "vt/scene/camera.hpp"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace vt {

glm::mat4 CameraView::view() const { return glm::inverse(T_world_eye); }

glm::mat4 CameraView::projection() const {
  // Off-axis perspective (as OpenXR gives per-eye fov), right-handed eye space, Vulkan clip:
  // x right, y down, z in [0,1].
  const float w = tanRight - tanLeft;
  const float h = tanUp - tanDown;
  glm::mat4 p(0.0f);
  p[0][0] = 2.0f / w;
  p[1][1] = -2.0f / h;
  p[2][0] = (tanRight + tanLeft) / w;
  p[2][1] = -(tanUp + tanDown) / h;
  p[2][2] = -far_m / (far_m - near_m);
  p[2][3] = -1.0f;
  p[3][2] = -(far_m * near_m) / (far_m - near_m);
  return p;
}

void setSymmetricFov(CameraView& view, float fovY_rad, float aspect) {
  const float t = std::tan(fovY_rad * 0.5f);
  view.tanUp = t;
  view.tanDown = -t;
  view.tanRight = t * aspect;
  view.tanLeft = -t * aspect;
}

CameraView OrbitCamera::view(float aspect) const {
  const glm::vec3 forward{std::cos(pitch_rad) * std::sin(yaw_rad), std::sin(pitch_rad),
                          -std::cos(pitch_rad) * std::cos(yaw_rad)};
  const glm::vec3 eye = target - forward * distance_m;
  CameraView v;
  v.T_world_eye = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
  setSymmetricFov(v, fovY_rad, aspect);
  return v;
}

void OrbitCamera::stereoViews(float aspect, float ipd_m, CameraView out[2]) const {
  const CameraView mono = view(aspect);
  for (int eye = 0; eye < 2; ++eye) {
    out[eye] = mono;
    const float offset = (eye == 0 ? -0.5f : 0.5f) * ipd_m;
    out[eye].T_world_eye = mono.T_world_eye * glm::translate(glm::mat4(1.0f), glm::vec3(offset, 0, 0));
  }
}

}  // namespace vt
