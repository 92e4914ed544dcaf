#pragma once
// What one frame shows: plain data, no Vulkan types (the scene itself comes through
// Renderer::setScene). Any thread may build a FrameDesc; the render thread consumes it.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "vt/scene/camera.hpp"
#include "vt/scene/hand.hpp"

namespace vt::renderer {

/// One instanced hand primitive: a capsule from a_world to b_world (a sphere when they coincide).
struct HandPrimitive {
  glm::vec3 a_world{0.0f};
  glm::vec3 b_world{0.0f};
  float radius_m = 0.01f;
  glm::vec4 color{0.9f, 0.75f, 0.65f, 1.0f};  // linear RGB, alpha ignored
};

/// The hand primitives one frame can draw at most (two hands need ~100).
inline constexpr std::uint32_t kMaxHandPrimitives = 256;

/// A touch shown as a ring lying on the surface at the contact point.
struct ContactMarker {
  glm::vec3 position_m{0.0f};          // on the touched surface (world)
  glm::vec3 normal{0.0f, 1.0f, 0.0f};  // the surface's outer normal (world, unit); the ring lies across it
  float intensity = 0.0f;              // 0..1: the ring's radius and brightness grow with it
};

/// The contact markers one frame can draw at most (five fingertips per hand, with room to spare).
inline constexpr std::uint32_t kMaxContactMarkers = 16;

/// The hand's skin colour (linear RGBA), the same in every view of it.
inline constexpr glm::vec4 kHandColor{0.85f, 0.62f, 0.5f, 1.0f};

/// One hand drawn as the skinned hand mesh (Renderer::setHandModel; left hands mirrored).
struct SkinnedHand {
  HandPose pose;
  bool left = false;
  glm::vec4 color = kHandColor;  // linear RGB, alpha ignored
};

/// The skinned hands one frame can draw at most.
inline constexpr std::uint32_t kMaxSkinnedHands = 2;

/// How a hand is drawn: the skinned mesh, or joint spheres and bone capsules (`--hand skeleton`).
enum class HandStyle { Mesh, Skeleton };

/// Everything that changes per frame.
struct FrameDesc {
  std::vector<CameraView> views;           // 1 (mono) or 2 (left, right); must equal target layers
  std::vector<HandPrimitive> hand;         // at most kMaxHandPrimitives
  std::vector<SkinnedHand> hands;          // at most kMaxSkinnedHands
  std::vector<ContactMarker> contacts;     // at most kMaxContactMarkers
  bool overlay = false;                    // vibration map as a heat colour over tactile surfaces
  float overlayOpacity = 0.6f;             // 0..1
  glm::vec4 clearColor{0.55f, 0.62f, 0.70f, 1.0f};  // linear RGB
  bool ui = true;  // run the pass hook (the ImGui layer) in this pass; false for targets it was not made for
};

/// Appends a sphere per joint and a capsule per bone of a hand pose (nothing when !pose.valid).
void appendHandPrimitives(const HandPose& pose, glm::vec4 color, std::vector<HandPrimitive>& out);
/// Adds a valid pose as a skinned hand or as primitives (kHandColor), as `style` says.
void appendHand(const HandPose& pose, HandStyle style, FrameDesc& frame, bool left = false);

}  // namespace vt::renderer
