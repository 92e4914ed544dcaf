#pragma once
// Pinhole camera with Vulkan conventions (clip Y down, depth 0..1), and stereo eye views.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace vt {

/// A view of the world: pose of the eye plus a symmetric or asymmetric frustum.
struct CameraView {
  glm::mat4 T_world_eye{1.0f};  // eye looks down its -Z, +Y up
  float tanLeft = -0.5f, tanRight = 0.5f, tanDown = -0.5f, tanUp = 0.5f;  // frustum half-angles as tangents
  float near_m = 0.02f, far_m = 20.0f;

  glm::mat4 view() const;
  /// Vulkan projection (Y flipped into clip space, reversed nothing, depth in [0,1]).
  glm::mat4 projection() const;
  glm::vec3 position() const { return glm::vec3(T_world_eye[3]); }
};

/// An orbit camera for the desktop preview and offscreen renders.
struct OrbitCamera {
  glm::vec3 target{0.0f, 0.0f, 0.0f};
  float distance_m = 0.8f;
  float yaw_rad = 0.0f;     // around +Y, 0 = looking down -Z
  float pitch_rad = -0.7f;  // negative looks down
  float fovY_rad = 0.9f;

  /// The single (mono) view for an image of the given aspect ratio.
  CameraView view(float aspect) const;
  /// Two eye views separated by ipd_m along the camera's right axis (left first).
  void stereoViews(float aspect, float ipd_m, CameraView out[2]) const;
};

/// A symmetric frustum from vertical field of view and aspect.
void setSymmetricFov(CameraView& view, float fovY_rad, float aspect);

}  // namespace vt
