#pragma once
// The desktop hand: a palm that follows the mouse over the surfaces, presses into them, moves
// with WASD/arrows and curls fingers on keys 1-5; plus the visual proxy that keeps drawn
// fingertips on the surface while the physical pose (the one the haptic loop reads) presses on.
#include <glm/glm.hpp>

#include "vt/collision/collision_scene.hpp"
#include "vt/scene/hand.hpp"

namespace vt::app {

/// Desktop hand state. Main thread only.
class DesktopHand {
 public:
  /// Fingertip height above the surface while not pressing (no contact).
  static constexpr float kHover_m = 0.008f;
  /// Press depth of the left mouse button; scroll adds to it (0..kMaxPress_m).
  static constexpr float kClickPress_m = 0.004f;
  static constexpr float kMaxPress_m = 0.03f;

  DesktopHand() { reset(); }
  /// Q: back to the start pose (above the scene centre, fingers straight, no press).
  void reset();
  /// Puts the index fingertip over `surface_world` (a point the mouse ray hit).
  void placeIndexTipOver(glm::vec3 surface_world);
  /// Keys (WASD: along the table, arrows up/down: height, left/right: turn) move the palm in
  /// steps of at most 2 mm; the motion stops where a fingertip of the unpressed hand (index to
  /// little) would sink deeper than kClickPress_m into a surface (as deep as a click presses),
  /// so no key pushes the hand through the table or a plate. A hand already deeper may still
  /// move where it gets no deeper.
  void move(glm::vec3 delta_m, float yaw_rad, const collision::CollisionScene& world);
  /// Extra press from the scroll wheel (clamped to 0..kMaxPress_m).
  void addPress(float delta_m);
  /// Keys 1-5: toggles a finger between straight and curled.
  void toggleCurl(int finger);
  /// Sets every curl target at once (a glove's measured flexion drives the fingers).
  void setCurlTargets(const FingerCurls& curls) { m_curlTargets = curls; }
  /// Eases curls towards their targets (call once per frame).
  void update(float dt_s);
  /// The physical pose; `pressing` = left button held. The pose's time is `t_ns`.
  HandPose pose(bool pressing, std::int64_t t_ns) const;

  float press_m(bool pressing) const;
  const FingerCurls& curls() const { return m_curls; }

 private:
  glm::vec3 m_palm_m{0.0f};  // palm centre at "hover" height
  float m_yaw_rad = 0.0f;
  float m_press_m = 0.0f;
  FingerCurls m_curls{}, m_curlTargets{};
};

/// The finger (0 thumb .. 4 little) a fingertip joint belongs to; 1 (index) for other joints.
int fingerOfTip(HandJoint joint) noexcept;
/// "thumb", "index", "middle", "ring", "little".
const char* fingerName(int finger) noexcept;

/// The pose to draw: every joint sphere that sinks into a surface is pushed back out along the
/// contact normal, so fingertips rest on the surface. Any thread (read-only queries).
HandPose visualProxy(const HandPose& physical, const collision::CollisionScene& world);

/// Where the ray from the camera through a pixel first meets the scene (or the table plane y = 0).
glm::vec3 pickSurface(const collision::CollisionScene& world, glm::vec3 origin, glm::vec3 direction);

}  // namespace vt::app
