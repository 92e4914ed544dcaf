#pragma once
// A hand mesh skinned to the 26 OpenXR hand joints: the generated default, its mirror for the left
// hand, the per-joint skinning matrices for a pose, and glTF skins a user can swap in
// (docs/renderer.md, "Hand model"). Setup thread only, except skinningMatrices (any thread).
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "vt/scene/hand.hpp"
#include "vt/scene/mesh.hpp"

namespace vt {

/// Triangles in the bind pose with up to four joint influences per vertex (linear blend skinning).
struct HandMesh {
  Mesh mesh;                                  // bind-pose positions and normals (uv unused)
  std::vector<glm::u8vec4> joints;            // per vertex: HandJoint indices
  std::vector<glm::vec4> weights;             // per vertex: weights of `joints`, summing to 1
  std::array<glm::mat4, kHandJointCount> inverseBind{};  // per joint: mesh frame <- joint frame at bind
  std::array<float, kFingerCount> tipRadius_m{};  // fingertip pad radius at bind; > 0: pads scale to the pose's tip radius
};

/// The generated right hand, bound in poseHand(identity, straight fingers): a rounded palm and a
/// tapered tube along each finger whose radius follows the pose's joint radii; each fingertip
/// ends in a hemisphere of the tip joint's radius around the tip joint, the sphere collision uses.
HandMesh makeHandMesh();

/// The left hand: the right one reflected across its palm's YZ plane (as poseHand mirrors poses).
HandMesh mirrorHandMesh(const HandMesh& right);

/// Per joint: T_world_joint(pose) * inverseBind, tip joints scaled by pose radius / tipRadius_m.
std::array<glm::mat4, kHandJointCount> skinningMatrices(const HandMesh& hand, const HandPose& pose) noexcept;

/// Throws vt::Error (prefixed by `source`) unless sizes agree, joints are in range and weights sum to 1.
void validateHandMesh(const HandMesh& hand, const std::string& source);

/// The joint's name in hand model files: "palm", "wrist", "thumb_metacarpal", ... "little_tip".
std::string_view handJointName(HandJoint joint) noexcept;
/// The joint named `name` (also accepted: any case, OpenXR's XR_HAND_JOINT_..._EXT spelling).
std::optional<HandJoint> handJointFromName(std::string_view name) noexcept;

/// Reads a .gltf/.glb whose first skinned mesh node has a skin with joints named after the OpenXR
/// joints. Throws vt::Error naming the file and the problem (no skin, unknown joint, > 4 weights...).
HandMesh loadHandModel(const std::filesystem::path& path);
/// Same from bytes already in memory (`.glb` when `binary`); `sourceName` names it in errors and
/// URIs resolve inside `baseDir`.
HandMesh loadHandModel(const std::string& bytes, bool binary, const std::string& sourceName,
                       const std::filesystem::path& baseDir);

/// Writes `hand` as such a glTF (.glb or .gltf + .bin); refuses an existing file unless `replace`.
void saveHandModel(const HandMesh& hand, const std::filesystem::path& path, bool replace);

}  // namespace vt
