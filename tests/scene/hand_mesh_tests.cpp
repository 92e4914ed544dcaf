// The skinned hand mesh on the CPU: bind pose, a bending finger, the fingertip pads, the mirror.
#include <catch2/catch.hpp>

#include <fstream>
#include <functional>
#include <map>
#include <utility>

#include <glm/gtc/epsilon.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "json_file.hpp"
#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/hand_mesh.hpp"

using namespace vt;

namespace {

constexpr FingerCurls kStraight{0, 0, 0, 0, 0};

// Linear blend skinning of one vertex, as shaders/skinned_hand.vert does it.
glm::vec3 skinned(const HandMesh& hand, const std::array<glm::mat4, kHandJointCount>& m, std::size_t v) {
  glm::mat4 blend(0.0f);
  for (int k = 0; k < 4; ++k) blend += hand.weights[v][k] * m[hand.joints[v][k]];
  return glm::vec3(blend * glm::vec4(hand.mesh.vertices[v].position, 1.0f));
}

bool onlyJoint(const HandMesh& hand, std::size_t v, HandJoint j) {
  return hand.joints[v][0] == std::uint8_t(j) && hand.weights[v][0] == 1.0f;
}

glm::mat4 frameOf(const HandPose& pose, HandJoint j) {
  glm::mat4 T = glm::mat4_cast(pose.orientation[std::size_t(j)]);
  T[3] = glm::vec4(pose.at(j), 1.0f);
  return T;
}

// Six times the enclosed volume: positive when every triangle winds counter-clockwise from outside.
double signedVolume6(const Mesh& mesh) {
  double sum = 0.0;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::dvec3 a = mesh.vertices[mesh.indices[t]].position, b = mesh.vertices[mesh.indices[t + 1]].position,
                     c = mesh.vertices[mesh.indices[t + 2]].position;
    sum += glm::dot(a, glm::cross(b, c));
  }
  return sum;
}

}  // namespace

TEST_CASE("The generated hand is closed, wound outwards and validly skinned", "[hand][mesh]") {
  const HandMesh hand = makeHandMesh();
  REQUIRE_NOTHROW(validateHandMesh(hand, "generated"));
  CHECK(hand.mesh.vertices.size() > 2000);
  // Closed surfaces: every directed edge appears once and its reverse once.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (std::size_t t = 0; t < hand.mesh.indices.size(); t += 3) {
    for (int e = 0; e < 3; ++e) ++edges[{hand.mesh.indices[t + e], hand.mesh.indices[t + (e + 1) % 3]}];
  }
  bool closed = true;
  for (const auto& [edge, count] : edges) closed = closed && count == 1 && edges.count({edge.second, edge.first}) == 1;
  CHECK(closed);
  // A hand's volume is a few hundred cm^3; positive = outward winding (back faces are culled).
  const double volume_cm3 = signedVolume6(hand.mesh) / 6.0 * 1e6;
  CHECK(volume_cm3 > 150.0);
  CHECK(volume_cm3 < 800.0);
  CHECK(signedVolume6(mirrorHandMesh(hand).mesh) / 6.0 * 1e6 == Approx(volume_cm3).epsilon(1e-4));
}

TEST_CASE("Skinning matrices are the identity in the bind pose, for both hands", "[hand][mesh]") {
  const HandMesh right = makeHandMesh();
  const HandMesh left = mirrorHandMesh(right);
  for (const bool isLeft : {false, true}) {
    const auto m = skinningMatrices(isLeft ? left : right, poseHand(glm::mat4(1.0f), kStraight, isLeft));
    for (std::size_t j = 0; j < kHandJointCount; ++j) {
      INFO("joint " << j << (isLeft ? " left" : " right"));
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) CHECK(m[j][c][r] == Approx(c == r ? 1.0f : 0.0f).margin(1e-5));
    }
  }
  // The left hand is the right one reflected in x: its thumb lies on the other side.
  const Aabb r = bounds(right.mesh), l = bounds(left.mesh);
  CHECK(l.min.x == Approx(-r.max.x).margin(1e-6));
  CHECK(l.max.x == Approx(-r.min.x).margin(1e-6));
}

TEST_CASE("A bent index finger carries its tip vertices with the joints and leaves the others", "[hand][mesh]") {
  const HandMesh hand = makeHandMesh();
  const glm::mat4 T_world_palm = glm::rotate(glm::translate(glm::mat4(1.0f), {0.1f, 0.2f, -0.3f}), 0.4f, glm::vec3(0, 1, 0));
  const HandPose bind = poseHand(glm::mat4(1.0f), kStraight);
  const HandPose bent = poseHand(T_world_palm, {0.0f, 1.0f, 0.0f, 0.0f, 0.0f});
  const auto m = skinningMatrices(hand, bent);
  std::size_t distal = 0, little = 0, pad = 0;
  float padTravel_m = 0.0f;
  for (std::size_t v = 0; v < hand.mesh.vertices.size(); ++v) {
    const glm::vec3 p = skinned(hand, m, v);
    const glm::vec3 rest = hand.mesh.vertices[v].position;
    if (onlyJoint(hand, v, HandJoint::IndexDistal)) {
      // Rigid with the distal joint: the same coordinates in its frame as in the bind pose.
      const glm::vec3 local = glm::vec3(glm::inverse(frameOf(bent, HandJoint::IndexDistal)) * glm::vec4(p, 1.0f));
      const glm::vec3 bindLocal = glm::vec3(glm::inverse(frameOf(bind, HandJoint::IndexDistal)) * glm::vec4(rest, 1.0f));
      CHECK(glm::distance(local, bindLocal) < 1e-5f);
      ++distal;
    }
    if (onlyJoint(hand, v, HandJoint::IndexTip)) {
      CHECK(glm::distance(p, bent.at(HandJoint::IndexTip)) == Approx(bent.radius_m[std::size_t(HandJoint::IndexTip)]).margin(1e-5));
      padTravel_m = std::max(padTravel_m, glm::distance(p, glm::vec3(T_world_palm * glm::vec4(rest, 1.0f))));
      ++pad;
    }
    if (onlyJoint(hand, v, HandJoint::LittleIntermediate)) {
      // Untouched by the index's bend: only the palm's transform applies.
      CHECK(glm::distance(p, glm::vec3(T_world_palm * glm::vec4(rest, 1.0f))) < 1e-5f);
      ++little;
    }
  }
  CHECK(distal > 20);
  CHECK(little > 20);
  CHECK(pad > 20);
  CHECK(padTravel_m > 0.05f);  // a curled index's tip ends up several centimetres from where it was
}

TEST_CASE("Fingertip pads are spheres of the radius collision uses", "[hand][mesh]") {
  const HandMesh hand = makeHandMesh();
  HandPose pose = poseHand(glm::mat4(1.0f), kStraight);
  // The haptic loop's contact sphere: the pose's tip radius, kDefaultFingertipRadius_m when it has none.
  CHECK(pose.radius_m[std::size_t(HandJoint::IndexTip)] == kDefaultFingertipRadius_m);
  CHECK(hand.tipRadius_m[std::size_t(Finger::Index)] == kDefaultFingertipRadius_m);
  pose.radius_m[std::size_t(HandJoint::MiddleTip)] = 0.011f;  // a runtime reporting a bigger pad
  const auto m = skinningMatrices(hand, pose);
  for (int f = 0; f < kFingerCount; ++f) {
    const HandJoint tip = kFingertips[std::size_t(f)];
    float nearest = 1.0f, farthest = 0.0f;
    for (std::size_t v = 0; v < hand.mesh.vertices.size(); ++v) {
      if (!onlyJoint(hand, v, tip)) continue;
      const float d = glm::distance(skinned(hand, m, v), pose.at(tip));
      nearest = std::min(nearest, d);
      farthest = std::max(farthest, d);
    }
    INFO("finger " << f);
    CHECK(nearest == Approx(pose.radius_m[std::size_t(tip)]).margin(1e-5));
    CHECK(farthest == Approx(pose.radius_m[std::size_t(tip)]).margin(1e-5));
  }
}

TEST_CASE("Hand joint names follow OpenXR", "[hand][mesh]") {
  CHECK(handJointName(HandJoint::LittleIntermediate) == "little_intermediate");
  CHECK(handJointFromName("index_tip") == HandJoint::IndexTip);
  CHECK(handJointFromName("XR_HAND_JOINT_THUMB_METACARPAL_EXT") == HandJoint::ThumbMetacarpal);
  CHECK(handJointFromName("Palm") == HandJoint::Palm);
  CHECK_FALSE(handJointFromName("pinky_tip").has_value());
  CHECK_FALSE(handJointFromName("xr_hand_joint__ext").has_value());
}

TEST_CASE("A hand mesh with bad weights or joints is refused, naming the problem", "[hand][mesh]") {
  HandMesh hand = makeHandMesh();
  hand.weights[7] = {0.5f, 0.2f, 0.0f, 0.0f};
  CHECK_THROWS_WITH(validateHandMesh(hand, "test.gltf"), Catch::Contains("test.gltf") && Catch::Contains("vertex 7"));
  hand = makeHandMesh();
  hand.joints[3][1] = 30;
  CHECK_THROWS_WITH(validateHandMesh(hand, "x"), Catch::Contains("joint 30"));
  hand = makeHandMesh();
  hand.weights.pop_back();
  CHECK_THROWS_WITH(validateHandMesh(hand, "x"), Catch::Contains("count"));
}

TEST_CASE("The generated hand round-trips through a glTF skin", "[hand][mesh][gltf]") {
  const HandMesh hand = makeHandMesh();
  const auto dir = test::outputDir("hand_gltf_round_trip");
  for (const char* name : {"hand.glb", "hand.gltf"}) {
    INFO(name);
    saveHandModel(hand, dir / name, true);
    CHECK_THROWS_WITH(saveHandModel(hand, dir / name, false), Catch::Contains("--force"));
    const HandMesh loaded = loadHandModel(dir / name);
    REQUIRE(loaded.mesh.vertices.size() == hand.mesh.vertices.size());
    CHECK(loaded.mesh.indices == hand.mesh.indices);
    CHECK(loaded.tipRadius_m == hand.tipRadius_m);
    CHECK(loaded.joints == hand.joints);
    bool same = true;
    for (std::size_t v = 0; v < hand.mesh.vertices.size(); ++v) {
      same = same && loaded.mesh.vertices[v].position == hand.mesh.vertices[v].position &&
             loaded.mesh.vertices[v].normal == hand.mesh.vertices[v].normal &&
             glm::all(glm::epsilonEqual(loaded.weights[v], hand.weights[v], 1e-6f));
    }
    CHECK(same);
    CHECK(loaded.inverseBind == hand.inverseBind);
  }
  // The joint nodes hold the bind pose: each node's world transform is the inverse bind matrix's inverse.
  const nlohmann::json doc = readJson(dir / "hand.gltf");
  REQUIRE(doc["skins"].size() == 1);
  CHECK(doc["nodes"][int(HandJoint::IndexTip)]["name"] == "index_tip");
  CHECK(doc["skins"][0]["joints"].size() == std::size_t(kHandJointCount));
}

TEST_CASE("A bad hand model is refused with one line naming the file and the problem", "[hand][mesh][gltf]") {
  const auto dir = test::outputDir("hand_gltf_errors");
  saveHandModel(makeHandMesh(), dir / "good.gltf", true);
  const nlohmann::json good = readJson(dir / "good.gltf");
  auto refused = [&](const std::string& name, const std::function<void(nlohmann::json&)>& change) {
    nlohmann::json doc = good;
    change(doc);
    std::filesystem::copy_file(dir / "good.bin", dir / (name + ".bin"), std::filesystem::copy_options::overwrite_existing);
    doc["buffers"][0]["uri"] = name + ".bin";
    writeJson(dir / (name + ".gltf"), doc);
    try {
      loadHandModel(dir / (name + ".gltf"));
    } catch (const Error& e) {
      const std::string message = e.what();
      CHECK(message.find('\n') == std::string::npos);
      CHECK_THAT(message, Catch::Contains(name + ".gltf"));
      return message;
    }
    FAIL("no error for " << name);
    return std::string();
  };
  CHECK_THAT(refused("no_skin", [](nlohmann::json& d) { d["nodes"][kHandJointCount].erase("skin"); }), Catch::Contains("no skinned mesh"));
  CHECK_THAT(refused("unknown_joint", [](nlohmann::json& d) { d["nodes"][7]["name"] = "pinky"; }),
             Catch::Contains("skin joint 7 'pinky' is not an OpenXR hand joint") && Catch::Contains("index_proximal"));
  CHECK_THAT(refused("twice", [](nlohmann::json& d) { d["nodes"][8]["name"] = "index_proximal"; }), Catch::Contains("appears twice"));
  CHECK_THAT(refused("eight_weights",
                     [](nlohmann::json& d) {
                       auto& attributes = d["meshes"][0]["primitives"][0]["attributes"];
                       attributes["JOINTS_1"] = attributes["JOINTS_0"];
                       attributes["WEIGHTS_1"] = attributes["WEIGHTS_0"];
                     }),
             Catch::Contains("more than 4 joint weights"));
  CHECK_THAT(refused("unskinned",
                     [](nlohmann::json& d) { d["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_0"); }),
             Catch::Contains("without JOINTS_0 and WEIGHTS_0"));
  CHECK_THAT(refused("short_ibm", [](nlohmann::json& d) { d["accessors"][d["skins"][0]["inverseBindMatrices"].get<int>()]["count"] = 3; }),
             Catch::Contains("26 joints but 3 inverse bind matrices"));
  CHECK_THROWS_WITH(loadHandModel(dir / "missing.glb"), Catch::Contains("missing.glb"));
}
