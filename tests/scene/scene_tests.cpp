#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "vt/core/error.hpp"
#include "vt/scene/camera.hpp"
#include "vt/scene/demo_scene.hpp"
#include "vt/scene/hand.hpp"
#include "vt/scene/mesh.hpp"

TEST_CASE("Box top face faces up with upright UVs") {
  const vt::Mesh box = vt::makeBox({2.0f, 1.0f, 2.0f});
  REQUIRE(box.triangleCount() == 12);
  // The first quad is the top; v grows toward -Z so the image's top row is the far edge.
  CHECK(box.vertices[0].normal == glm::vec3(0, 1, 0));
  CHECK(box.vertices[0].position == glm::vec3(-1, 0.5f, 1));
  CHECK(box.vertices[0].uv == glm::vec2(0, 0));
  CHECK(box.vertices[3].position == glm::vec3(-1, 0.5f, -1));
  CHECK(box.vertices[3].uv == glm::vec2(0, 1));
  const vt::Aabb b = vt::bounds(box);
  CHECK(b.min == glm::vec3(-1, -0.5f, -1));
  CHECK(b.max == glm::vec3(1, 0.5f, 1));
}

TEST_CASE("Camera projects its target to the image centre with depth in (0,1)") {
  vt::OrbitCamera orbit;
  orbit.target = {0.1f, 0.0f, -0.2f};
  const vt::CameraView view = orbit.view(16.0f / 9.0f);
  const glm::vec4 clip = view.projection() * view.view() * glm::vec4(orbit.target, 1.0f);
  CHECK(clip.x / clip.w == Approx(0.0f).margin(1e-5));
  CHECK(clip.y / clip.w == Approx(0.0f).margin(1e-5));
  CHECK(clip.z / clip.w > 0.0f);
  CHECK(clip.z / clip.w < 1.0f);
  // A point above the target lands in the upper half: Vulkan clip y points down.
  const glm::vec4 up = view.projection() * view.view() * glm::vec4(orbit.target + glm::vec3(0, 0.05f, 0), 1.0f);
  CHECK(up.y / up.w < 0.0f);
}

TEST_CASE("Stereo eyes are separated by the IPD along the camera's right axis") {
  vt::OrbitCamera orbit;
  vt::CameraView eyes[2];
  orbit.stereoViews(1.0f, 0.064f, eyes);
  CHECK(glm::distance(eyes[0].position(), eyes[1].position()) == Approx(0.064f).epsilon(1e-4));
  const glm::vec3 right = glm::vec3(eyes[0].T_world_eye[0]);
  CHECK(glm::dot(eyes[1].position() - eyes[0].position(), right) > 0.0f);
}

TEST_CASE("Open hand fingertips lie ahead of the palm at anatomical distances and curling pulls them in") {
  const glm::mat4 T_world_palm = glm::translate(glm::mat4(1.0f), {0.0f, 0.1f, 0.0f});
  const vt::HandPose open = vt::poseHand(T_world_palm, {0, 0, 0, 0, 0});
  REQUIRE(open.valid);
  const glm::vec3 palm = open.at(vt::HandJoint::Palm);
  const float indexReach = glm::distance(palm, open.at(vt::HandJoint::IndexTip));
  CHECK(indexReach > 0.10f);
  CHECK(indexReach < 0.16f);
  CHECK(open.at(vt::HandJoint::IndexTip).z < palm.z);  // fingers point along -Z
  const vt::HandPose fist = vt::poseHand(T_world_palm, {1, 1, 1, 1, 1});
  CHECK(glm::distance(palm, fist.at(vt::HandJoint::IndexTip)) < indexReach * 0.7f);
  CHECK(fist.at(vt::HandJoint::IndexTip).y < palm.y);  // curls toward the palm side (-Y)
  // A left hand mirrors the thumb to the other side.
  const vt::HandPose left = vt::poseHand(T_world_palm, {0, 0, 0, 0, 0}, true);
  CHECK(open.at(vt::HandJoint::ThumbTip).x < 0.0f);
  CHECK(left.at(vt::HandJoint::ThumbTip).x > 0.0f);
}

TEST_CASE("Joint orientations follow the OpenXR convention: -Z along the bone") {
  const vt::HandPose open = vt::poseHand(glm::mat4(1.0f), {0, 0.5f, 0, 0, 0});
  const auto i = std::size_t(vt::HandJoint::IndexIntermediate);
  const glm::vec3 bone = glm::normalize(open.position[i + 1] - open.position[i]);
  const glm::vec3 minusZ = open.orientation[i] * glm::vec3(0, 0, -1);
  CHECK(glm::dot(bone, minusZ) == Approx(1.0f).margin(1e-4));
}

TEST_CASE("Demo scene validates and a variant changes its textures") {
  const vt::Scene a = vt::makeDemoScene({.textureSize = 32});
  REQUIRE_NOTHROW(a.validate());
  CHECK(a.objects.size() == 5);
  CHECK(a.vibrationMaps.size() == 4);
  const vt::Scene b = vt::makeDemoScene({.textureSize = 32, .variant = 1});
  CHECK(a.textures[1].pixels != b.textures[1].pixels);
  vt::Scene broken = a;
  broken.objects[1].material = 42;
  REQUIRE_THROWS_AS(broken.validate(), vt::Error);
}

TEST_CASE("The tactile digest follows what can be touched and ignores looks") {
  const vt::Scene a = vt::makeDemoScene();
  const vt::Scene b = vt::makeDemoScene();
  CHECK(vt::tactileDigest(a) == vt::tactileDigest(b));
  vt::Scene recoloured = b;
  recoloured.materials[0].baseColor = glm::vec4(0.1f, 0.2f, 0.3f, 1.0f);
  CHECK(vt::tactileDigest(recoloured) == vt::tactileDigest(a));
  vt::Scene moved = b;
  moved.objects[0].T_world_object[3].x += 0.001f;
  CHECK(vt::tactileDigest(moved) != vt::tactileDigest(a));
  vt::Scene remapped = b;
  REQUIRE(!remapped.vibrationMaps.empty());
  remapped.vibrationMaps[0].pixels[0] += 0.5f;
  CHECK(vt::tactileDigest(remapped) != vt::tactileDigest(a));
}

TEST_CASE("Computed normals are unit vectors for coordinates near a float's limits") {
  // Found by fuzz_gltf's export check: float cross products of such edges overflowed, and the
  // normal came out NaN (which the exported file then carried and its reload refused).
  for (const float size : {1.0e20f, 3.0e38f, 1.0e-30f, 1.0f}) {  // 1e20: a cross product overflows to inf, not NaN
    vt::Mesh mesh;
    mesh.vertices = {{{-size, 0.0f, -size}}, {{size, 0.0f, size}}, {{size, 0.0f, -size}}, {{-size, 0.0f, size}}};
    mesh.indices = {0, 1, 2, 0, 3, 1};
    vt::computeNormals(mesh);
    for (const vt::Vertex& v : mesh.vertices) {
      CHECK(v.normal.x == 0.0f);
      CHECK(v.normal.y == Approx(1.0f));
      CHECK(v.normal.z == 0.0f);
    }
  }
}
