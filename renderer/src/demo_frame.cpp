#include "vt/renderer/demo_frame.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace vt::renderer {

FrameDesc makeDemoFrame(const Scene& scene, std::uint32_t width, std::uint32_t height, bool stereo, bool overlay,
                        HandStyle hand) {
  FrameDesc frame;
  const float aspect = float(width) / float(height);
  if (stereo) {
    CameraView eyes[2];
    scene.camera.stereoViews(aspect, kDefaultIpd_m, eyes);
    frame.views = {eyes[0], eyes[1]};
  } else {
    frame.views = {scene.camera.view(aspect)};
  }
  frame.overlay = overlay;
  // Palm 6 cm above the second plate, fingers pointing away from the viewer, index finger extended
  // as if about to stroke the surface.
  const glm::mat4 T_world_palm = glm::rotate(glm::translate(glm::mat4(1.0f), {-0.07f, 0.07f, 0.12f}), -0.3f,
                                             glm::vec3(1.0f, 0.0f, 0.0f));
  const HandPose pose = poseHand(T_world_palm, {0.3f, 0.05f, 0.6f, 0.7f, 0.75f});
  appendHand(pose, hand, frame);
  return frame;
}

}  // namespace vt::renderer
