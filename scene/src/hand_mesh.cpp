#include "vt/scene/hand_mesh.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "vt/core/error.hpp"

namespace vt {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr int kRingVertices = 20;   // around a finger
constexpr int kPalmRingVertices = 36;
constexpr int kCapRings = 6;        // rings of a hemispherical end, pole excluded
constexpr float kRingStep_m = 0.003f;

using Skin = std::pair<glm::u8vec4, glm::vec4>;

Skin single(HandJoint j) { return {{std::uint8_t(j), 0, 0, 0}, {1, 0, 0, 0}}; }
Skin blend(HandJoint a, HandJoint b, float t) {
  if (t <= 0.0f || t >= 1.0f) return single(t <= 0.0f ? a : b);
  return {{std::uint8_t(a), std::uint8_t(b), 0, 0}, {1.0f - t, t, 0, 0}};
}
float smooth(float lo, float hi, float x) {
  const float t = std::clamp((x - lo) / (hi - lo), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

/// One cross-section of a tube: a superellipse (exponent 2 = ellipse) in the plane of side, up.
struct Ring {
  glm::vec3 centre, side, up;
  float halfWidth, halfHeight;
  float exponent = 2.0f;
  Skin skin;
};

float signedPow(float x, float p) { return std::copysign(std::pow(std::abs(x), p), x); }

/// A closed tube through `rings`, each end closed by a pole vertex; wound counter-clockwise seen
/// from outside whichever way side x up points along the tube.
void addTube(HandMesh& out, const std::vector<Ring>& rings, glm::vec3 startPole, glm::vec3 endPole, int around) {
  Mesh& m = out.mesh;
  const auto first = std::uint32_t(m.vertices.size());
  auto vertex = [&](glm::vec3 p, const Skin& s) {
    m.vertices.push_back({p, {0, 1, 0}, {0, 0}});
    out.joints.push_back(s.first);
    out.weights.push_back(s.second);
  };
  vertex(startPole, rings.front().skin);
  for (const Ring& r : rings) {
    for (int k = 0; k < around; ++k) {
      const float a = 2.0f * kPi * float(k) / float(around);
      const float e = 2.0f / r.exponent;
      vertex(r.centre + r.side * (r.halfWidth * signedPow(std::cos(a), e)) + r.up * (r.halfHeight * signedPow(std::sin(a), e)),
             r.skin);
    }
  }
  vertex(endPole, rings.back().skin);
  const glm::vec3 along = rings.back().centre - rings.front().centre;
  const bool flip = glm::dot(glm::cross(rings.front().side, rings.front().up), along) < 0.0f;
  auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (flip) std::swap(b, c);
    m.indices.insert(m.indices.end(), {a, b, c});
  };
  const auto n = std::uint32_t(around);
  auto at = [&](std::size_t ring, std::uint32_t k) { return first + 1 + std::uint32_t(ring) * n + k % n; };
  const std::uint32_t endIndex = first + 1 + std::uint32_t(rings.size()) * n;
  for (std::uint32_t k = 0; k < n; ++k) {
    tri(first, at(0, k + 1), at(0, k));
    for (std::size_t r = 0; r + 1 < rings.size(); ++r) {
      tri(at(r, k), at(r, k + 1), at(r + 1, k + 1));
      tri(at(r, k), at(r + 1, k + 1), at(r + 1, k));
    }
    tri(endIndex, at(rings.size() - 1, k), at(rings.size() - 1, k + 1));
  }
}

/// Rings of a rounded end beyond `base` (pointing along `out`): the section shrinks as a
/// quarter circle over `length`; returns the pole. With a circular section of radius r and
/// length r this is a hemisphere.
glm::vec3 capRings(const Ring& base, glm::vec3 out, float length, std::vector<Ring>& rings, bool prepend) {
  std::vector<Ring> cap;
  for (int i = 1; i <= kCapRings; ++i) {
    const float phi = 0.5f * kPi * float(i) / float(kCapRings + 1);
    Ring r = base;
    r.centre = base.centre + out * (length * std::sin(phi));
    r.halfWidth = base.halfWidth * std::cos(phi);
    r.halfHeight = base.halfHeight * std::cos(phi);
    cap.push_back(r);
  }
  if (prepend) rings.insert(rings.begin(), cap.rbegin(), cap.rend());
  else rings.insert(rings.end(), cap.begin(), cap.end());
  return base.centre + out * length;
}

glm::vec3 axisOf(const HandPose& pose, HandJoint j, int axis) {
  return glm::mat3_cast(pose.orientation[std::size_t(j)])[axis];
}

/// One finger: a tube from behind its first joint to a hemisphere around the tip joint. Bone
/// i (joint i to i + 1) follows joint i; each inner joint blends its two bones over a window
/// of ~0.7 radius, and the tip joint takes over along the second half of the last bone (so a
/// scaled pad tapers smoothly into the finger).
void addFinger(HandMesh& out, const HandPose& pose, const std::vector<HandJoint>& chain) {
  std::vector<float> s(chain.size(), 0.0f);
  for (std::size_t i = 1; i < chain.size(); ++i) s[i] = s[i - 1] + glm::distance(pose.at(chain[i - 1]), pose.at(chain[i]));
  auto radius = [&](std::size_t i) { return pose.radius_m[std::size_t(chain[i])]; };
  const HandJoint before = parentJoint(chain.front());
  const float back = radius(0);  // the tube starts this far behind the first joint, inside the palm
  auto skinAt = [&](float x) -> Skin {
    const std::size_t last = chain.size() - 1;
    const float tipStart = s[last] - 0.5f * (s[last] - s[last - 1]);
    if (x >= tipStart) return blend(chain[last - 1], chain[last], smooth(tipStart, s[last], x));
    for (std::size_t i = last - 1;; --i) {
      const float w = 0.7f * radius(i);
      if (x >= s[i] - w) {
        const HandJoint previous = i == 0 ? before : chain[i - 1];
        return x >= s[i] + w ? single(chain[i]) : blend(previous, chain[i], smooth(s[i] - w, s[i] + w, x));
      }
      if (i == 0) return single(before);
    }
  };
  auto ringAt = [&](float x) {
    // Segment containing x (before the first joint: the first bone extended backwards).
    std::size_t i = 0;
    while (i + 2 < chain.size() && x > s[i + 1]) ++i;
    const float t = std::clamp((x - s[i]) / (s[i + 1] - s[i]), x < 0.0f ? -10.0f : 0.0f, 1.0f);
    const HandJoint j = chain[i];
    Ring r;
    r.centre = glm::mix(pose.at(chain[i]), pose.at(chain[i + 1]), t);
    r.side = axisOf(pose, j, 0);
    r.up = axisOf(pose, j, 1);
    r.halfWidth = r.halfHeight = glm::mix(radius(i), radius(i + 1), std::max(t, 0.0f));
    r.skin = skinAt(x);
    return r;
  };
  std::vector<Ring> rings;
  const float length = s.back() + back;
  const int steps = std::max(4, int(std::ceil(length / kRingStep_m)));
  for (int k = 0; k <= steps; ++k) rings.push_back(ringAt(-back + length * float(k) / float(steps)));
  const glm::vec3 forward = -axisOf(pose, chain.back(), 2);
  const glm::vec3 backward = axisOf(pose, chain.front(), 2);
  const Ring startRing = rings.front(), endRing = rings.back();
  const glm::vec3 startPole = capRings(startRing, backward, startRing.halfWidth, rings, true);
  const glm::vec3 endPole = capRings(endRing, forward, endRing.halfWidth, rings, false);
  addTube(out, rings, startPole, endPole, kRingVertices);
}

/// The palm: a lofted rounded slab from past the wrist to the knuckles, skinned across the four
/// finger metacarpals and, towards the wrist, to the wrist joint.
void addPalm(HandMesh& out, const HandPose& pose) {
  const std::array<HandJoint, 4> metacarpals = {HandJoint::IndexMetacarpal, HandJoint::MiddleMetacarpal,
                                                HandJoint::RingMetacarpal, HandJoint::LittleMetacarpal};
  const glm::vec3 indexKnuckle = pose.at(HandJoint::IndexProximal), littleKnuckle = pose.at(HandJoint::LittleProximal);
  const glm::vec3 wrist = pose.at(HandJoint::Wrist);
  float knuckleZ = 0.0f, knuckleR = 0.0f;
  for (HandJoint m : metacarpals) {
    knuckleZ += 0.25f * pose.at(HandJoint(int(m) + 1)).z;
    knuckleR += 0.25f * pose.radius_m[std::size_t(m) + 1];
  }
  const float knuckleHalfWidth = 0.5f * (littleKnuckle.x - indexKnuckle.x) + knuckleR;
  const float knuckleX = 0.5f * (littleKnuckle.x + indexKnuckle.x);
  // Sections in the palm frame (bind = palm at the origin): z, centre x, centre y, half width, half height.
  struct Section { float z, x, y, a, b; };
  const std::array<Section, 4> sections = {{
      {wrist.z, wrist.x, -0.002f, 0.62f * knuckleHalfWidth, 1.35f * knuckleR},
      {0.5f * wrist.z, 0.5f * (wrist.x + knuckleX), -0.004f, 0.86f * knuckleHalfWidth, 1.5f * knuckleR},
      {0.0f, knuckleX, -0.004f, knuckleHalfWidth, 1.45f * knuckleR},
      {knuckleZ + 0.004f, knuckleX, -0.002f, knuckleHalfWidth, 1.1f * knuckleR},
  }};
  auto skinAt = [&](glm::vec3 p) -> Skin {
    std::size_t a = 0;
    while (a + 2 < metacarpals.size() && p.x > pose.at(HandJoint(int(metacarpals[a + 1]) + 1)).x) ++a;
    const float xa = pose.at(HandJoint(int(metacarpals[a]) + 1)).x, xb = pose.at(HandJoint(int(metacarpals[a + 1]) + 1)).x;
    const float t = std::clamp((p.x - xa) / (xb - xa), 0.0f, 1.0f);
    const float toWrist = smooth(0.5f * wrist.z, wrist.z, p.z);
    return {{std::uint8_t(metacarpals[a]), std::uint8_t(metacarpals[a + 1]), std::uint8_t(HandJoint::Wrist), 0},
            {(1.0f - t) * (1.0f - toWrist), t * (1.0f - toWrist), toWrist, 0.0f}};
  };
  std::vector<Ring> rings;
  constexpr int kSteps = 28;
  for (int k = 0; k <= kSteps; ++k) {
    const float z = sections.front().z + (sections.back().z - sections.front().z) * float(k) / float(kSteps);
    std::size_t i = 0;
    while (i + 2 < sections.size() && z < sections[i + 1].z) ++i;
    const Section &lo = sections[i], &hi = sections[i + 1];
    const float t = (z - lo.z) / (hi.z - lo.z);
    Ring r;
    r.centre = {glm::mix(lo.x, hi.x, t), glm::mix(lo.y, hi.y, t), z};
    r.side = {1, 0, 0};
    r.up = {0, 1, 0};
    r.halfWidth = glm::mix(lo.a, hi.a, t);
    r.halfHeight = glm::mix(lo.b, hi.b, t);
    r.exponent = 2.6f;
    rings.push_back(r);
  }
  const Ring startRing = rings.front(), endRing = rings.back();
  const glm::vec3 startPole = capRings(startRing, {0, 0, 1}, 0.8f * startRing.halfHeight, rings, true);
  const glm::vec3 endPole = capRings(endRing, {0, 0, -1}, 1.2f * endRing.halfHeight, rings, false);
  const auto first = out.mesh.vertices.size();
  addTube(out, rings, startPole, endPole, kPalmRingVertices);
  for (std::size_t v = first; v < out.mesh.vertices.size(); ++v) {
    std::tie(out.joints[v], out.weights[v]) = skinAt(out.mesh.vertices[v].position);
  }
}

glm::mat4 jointFrame(const HandPose& pose, std::size_t j) {
  glm::mat4 T = glm::mat4_cast(pose.orientation[j]);
  T[3] = glm::vec4(pose.position[j], 1.0f);
  return T;
}

constexpr std::array<std::string_view, kHandJointCount> kJointNames = {
    "palm", "wrist",
    "thumb_metacarpal", "thumb_proximal", "thumb_distal", "thumb_tip",
    "index_metacarpal", "index_proximal", "index_intermediate", "index_distal", "index_tip",
    "middle_metacarpal", "middle_proximal", "middle_intermediate", "middle_distal", "middle_tip",
    "ring_metacarpal", "ring_proximal", "ring_intermediate", "ring_distal", "ring_tip",
    "little_metacarpal", "little_proximal", "little_intermediate", "little_distal", "little_tip"};

}  // namespace

HandMesh makeHandMesh() {
  const HandPose bind = poseHand(glm::mat4(1.0f), {0, 0, 0, 0, 0});
  HandMesh out;
  addPalm(out, bind);
  addFinger(out, bind, {HandJoint::ThumbMetacarpal, HandJoint::ThumbProximal, HandJoint::ThumbDistal, HandJoint::ThumbTip});
  for (int f = 1; f < kFingerCount; ++f) {
    const int proximal = 6 + 5 * (f - 1) + 1;
    addFinger(out, bind, {HandJoint(proximal), HandJoint(proximal + 1), HandJoint(proximal + 2), HandJoint(proximal + 3)});
  }
  computeNormals(out.mesh);
  // glTF wants unused influences to name joint 0.
  for (std::size_t v = 0; v < out.joints.size(); ++v) {
    for (int k = 0; k < 4; ++k) {
      if (out.weights[v][k] == 0.0f) out.joints[v][k] = 0;
    }
  }
  for (std::size_t j = 0; j < kHandJointCount; ++j) out.inverseBind[j] = glm::inverse(jointFrame(bind, j));
  for (int f = 0; f < kFingerCount; ++f) out.tipRadius_m[std::size_t(f)] = bind.radius_m[std::size_t(kFingertips[std::size_t(f)])];
  return out;
}

HandMesh mirrorHandMesh(const HandMesh& right) {
  // Reflection M across the palm's YZ plane, in the mesh frame: Mm = B M B^-1 with B the palm's
  // bind frame. Mirrored poses have T_left = W M T_right' M, so inverse binds become M IB Mm.
  const glm::mat4 M = glm::scale(glm::mat4(1.0f), {-1.0f, 1.0f, 1.0f});
  const glm::mat4 B = glm::inverse(right.inverseBind[std::size_t(HandJoint::Palm)]);
  const glm::mat4 Mm = B * M * glm::inverse(B);
  HandMesh left = right;
  for (Vertex& v : left.mesh.vertices) {
    v.position = glm::vec3(Mm * glm::vec4(v.position, 1.0f));
    v.normal = glm::normalize(glm::mat3(Mm) * v.normal);
  }
  for (std::size_t t = 0; t + 2 < left.mesh.indices.size(); t += 3) std::swap(left.mesh.indices[t + 1], left.mesh.indices[t + 2]);
  for (glm::mat4& ib : left.inverseBind) ib = M * ib * Mm;
  return left;
}

std::array<glm::mat4, kHandJointCount> skinningMatrices(const HandMesh& hand, const HandPose& pose) noexcept {
  std::array<glm::mat4, kHandJointCount> out;
  for (std::size_t j = 0; j < kHandJointCount; ++j) out[j] = jointFrame(pose, j);
  for (int f = 0; f < kFingerCount; ++f) {
    const auto tip = std::size_t(kFingertips[std::size_t(f)]);
    const float bindRadius = hand.tipRadius_m[std::size_t(f)], poseRadius = pose.radius_m[tip];
    if (bindRadius > 0.0f && poseRadius > 0.0f) out[tip] = glm::scale(out[tip], glm::vec3(poseRadius / bindRadius));
  }
  for (std::size_t j = 0; j < kHandJointCount; ++j) out[j] = out[j] * hand.inverseBind[j];
  return out;
}

void validateHandMesh(const HandMesh& hand, const std::string& source) {
  const std::size_t n = hand.mesh.vertices.size();
  if (n == 0 || hand.mesh.indices.empty()) fail(source, ": the hand mesh has no triangles");
  if (hand.joints.size() != n || hand.weights.size() != n) fail(source, ": joints/weights count differs from vertices");
  for (std::uint32_t i : hand.mesh.indices) {
    if (i >= n) fail(source, ": index ", i, " out of range (", n, " vertices)");
  }
  for (std::size_t v = 0; v < n; ++v) {
    for (int k = 0; k < 4; ++k) {
      if (hand.joints[v][k] >= kHandJointCount) fail(source, ": vertex ", v, " names joint ", int(hand.joints[v][k]));
    }
    const glm::vec4 w = hand.weights[v];
    const float sum = w.x + w.y + w.z + w.w;
    if (!(std::abs(sum - 1.0f) < 1e-3f) || glm::any(glm::lessThan(w, glm::vec4(0.0f)))) {
      fail(source, ": vertex ", v, " has weights that do not sum to 1 (", sum, ")");
    }
  }
}

std::string_view handJointName(HandJoint joint) noexcept { return kJointNames[std::size_t(joint)]; }

std::optional<HandJoint> handJointFromName(std::string_view name) noexcept {
  std::string lower;
  for (char c : name) lower.push_back(char(std::tolower(static_cast<unsigned char>(c))));
  constexpr std::string_view prefix = "xr_hand_joint_", suffix = "_ext";
  if (lower.starts_with(prefix) && lower.ends_with(suffix) && lower.size() > prefix.size() + suffix.size()) {
    lower = lower.substr(prefix.size(), lower.size() - prefix.size() - suffix.size());
  }
  for (std::size_t j = 0; j < kJointNames.size(); ++j) {
    if (kJointNames[j] == lower) return HandJoint(j);
  }
  return std::nullopt;
}

}  // namespace vt
