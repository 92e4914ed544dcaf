// Renderer behaviour beyond the goldens: stereo geometry, sRGB output, validation plumbing,
// misuse errors, device hooks and adoption. Validation layer on everywhere.
#include <cmath>
#include <cstdlib>

#include <catch2/catch.hpp>

#include "image_compare.hpp"
#include "render_fixture.hpp"
#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/renderer/demo_frame.hpp"
#include "vt/renderer/offscreen_target.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/renderer/vk_check.hpp"

using namespace vt;
using namespace vt::test;
using vt::renderer::Device;
using vt::renderer::FrameDesc;
using vt::renderer::OffscreenTarget;
using vt::renderer::Renderer;

namespace {

// Mean |right(x) - left(x + shift)| over the rows that show the plates.
double shiftedDifference(const Image8& left, const Image8& right, int shift) {
  double sum = 0.0;
  int n = 0;
  for (int y = left.height / 3; y < 2 * left.height / 3; ++y) {
    for (int x = 40; x < left.width - 40; ++x) {
      sum += std::abs(vt::test::luminance(right, x, y) - vt::test::luminance(left, x + shift, y));
      ++n;
    }
  }
  return sum / n;
}

FrameDesc clearOnlyFrame(glm::vec4 clear) {
  FrameDesc frame;
  frame.views = {CameraView{}};
  frame.clearColor = clear;
  return frame;
}

}  // namespace

TEST_CASE("stereo views differ by the eye offset", "[renderer]") {
  const auto eyes = renderDemo({}, true, false);
  REQUIRE(eyes.size() == 2);
  // The left eye sits ipd/2 to the left, so the scene appears shifted right in its image: the
  // right image matches the left one shifted by a positive disparity. Plates at ~0.75 m seen with
  // a focal length of ~186 px (180 px high, 0.9 rad fov) give 0.064 * 186 / 0.75 ~ 16 px.
  int best = 0;
  double bestDiff = 1e9;
  for (int shift = -35; shift <= 35; ++shift) {
    const double d = shiftedDifference(eyes[0], eyes[1], shift);
    if (d < bestDiff) {
      bestDiff = d;
      best = shift;
    }
  }
  const double unshifted = shiftedDifference(eyes[0], eyes[1], 0);
  INFO("best shift " << best << " px, difference " << bestDiff << " (unshifted " << unshifted << ")");
  CHECK(best >= 8);
  CHECK(best <= 28);
  CHECK(unshifted > 2.0 * bestDiff);
}

TEST_CASE("output is sRGB encoded", "[renderer]") {
  auto device = validatingDevice();
  {
    Renderer r(device);
    OffscreenTarget target(device, 16, 8);
    REQUIRE(r.render(target, clearOnlyFrame({0.5f, 0.2140f, 1.0f, 1.0f})));
    const Image8 image = target.readback();
    // Linear 0.5 -> sRGB 188, linear 0.214 -> 128 (the attachment encodes, nothing else does).
    CHECK(std::abs(int(image.at(5, 3, 0)) - 188) <= 1);
    CHECK(std::abs(int(image.at(5, 3, 1)) - 128) <= 1);
    CHECK(int(image.at(5, 3, 2)) == 255);
  }
  expectNoValidationMessages(*device);
}

TEST_CASE("offscreen readback copies the last frame, from whichever of its images it went to", "[renderer]") {
  auto device = validatingDevice();
  {
    Renderer r(device);
    OffscreenTarget target(device, 16, 8);
    // Frames alternate between the target's two images; only readback() copies, and only the last.
    const float reds[] = {1.0f, 0.0f, 1.0f, 0.0f};
    for (const float red : reds) {
      REQUIRE(r.render(target, clearOnlyFrame({red, 0.0f, 1.0f - red, 1.0f})));
      const Image8 image = target.readback();
      CHECK(int(image.at(7, 4, 0)) == int(red * 255.0f));
      CHECK(int(image.at(7, 4, 2)) == int((1.0f - red) * 255.0f));
    }
    REQUIRE(r.render(target, clearOnlyFrame({0.0f, 1.0f, 0.0f, 1.0f})));
    REQUIRE(r.render(target, clearOnlyFrame({1.0f, 1.0f, 1.0f, 1.0f})));  // two frames, one read
    CHECK(int(target.readback().at(0, 0, 0)) == 255);
    CHECK(int(target.readback().at(15, 7, 1)) == 255);
  }
  expectNoValidationMessages(*device);
}

TEST_CASE("a frame prepared ahead is drawn by the next render into that target, and only that target",
          "[renderer]") {
  auto device = validatingDevice();
  {
    Renderer r(device);
    OffscreenTarget target(device, 16, 8), other(device, 16, 8);
    // prepare() waits for the slot and acquires; render() then draws into that image. Repeated
    // preparation of the same target is one preparation; frames alternate images as before.
    for (const float red : {1.0f, 0.0f, 1.0f}) {
      REQUIRE(r.prepare(target));
      REQUIRE(r.prepare(target));
      REQUIRE(r.render(target, clearOnlyFrame({red, 0.0f, 1.0f - red, 1.0f})));
      CHECK(int(target.readback().at(7, 4, 0)) == int(red * 255.0f));
    }
    // With one target prepared, another can neither be prepared nor drawn into.
    REQUIRE(r.prepare(target));
    CHECK_THROWS_WITH(r.prepare(other), Catch::Contains("another target is prepared"));
    CHECK_THROWS_WITH(r.render(other, clearOnlyFrame({0.0f, 1.0f, 0.0f, 1.0f})), Catch::Contains("another target is prepared"));
    REQUIRE(r.render(target, clearOnlyFrame({0.0f, 1.0f, 0.0f, 1.0f})));
    CHECK(int(target.readback().at(0, 0, 1)) == 255);
    REQUIRE(r.render(other, clearOnlyFrame({0.0f, 0.0f, 1.0f, 1.0f})));  // unprepared: acquires itself
    CHECK(int(other.readback().at(0, 0, 2)) == 255);
  }
  expectNoValidationMessages(*device);
}

TEST_CASE("validation messages are counted", "[renderer]") {
  auto device = validatingDevice();
  REQUIRE(device->validationEnabled());
  REQUIRE(device->validationMessageCount() == 0);
  // A zero-sized buffer breaks VUID-VkBufferCreateInfo-size-00912: the layer reports it.
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 0;
  info.usage = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  const VkResult result = vkCreateBuffer(device->device(), &info, nullptr, &buffer);
  if (result == VK_SUCCESS && buffer) vkDestroyBuffer(device->device(), buffer, nullptr);
  CHECK(device->validationMessageCount() >= 1);
}

TEST_CASE("render rejects a view count that differs from the target layers", "[renderer]") {
  auto device = validatingDevice();
  {
    Renderer r(device);
    OffscreenTarget stereo(device, 16, 8, 2);
    CHECK_THROWS_WITH(r.render(stereo, clearOnlyFrame(glm::vec4(1.0f))), Catch::Contains("2 layers"));
    FrameDesc tooMany = clearOnlyFrame(glm::vec4(1.0f));
    tooMany.hand.resize(renderer::kMaxHandPrimitives + 1);
    OffscreenTarget mono(device, 16, 8, 1);
    CHECK_THROWS_WITH(r.render(mono, tooMany), Catch::Contains("hand primitives"));
    FrameDesc threeHands = clearOnlyFrame(glm::vec4(1.0f));
    threeHands.hands.resize(renderer::kMaxSkinnedHands + 1);
    CHECK_THROWS_WITH(r.render(mono, threeHands), Catch::Contains("3 skinned hands"));
    CHECK_THROWS_AS(OffscreenTarget(device, 0, 8), Error);
    CHECK_THROWS_AS(OffscreenTarget(device, 8, 8, 3), Error);
    CHECK_THROWS_WITH(OffscreenTarget(device, 8, 8).readback(), Catch::Contains("before any frame"));
  }
  expectNoValidationMessages(*device);
}

TEST_CASE("an invalid scene is refused naming the object", "[renderer]") {
  auto device = validatingDevice();
  {
    Renderer r(device);
    Scene scene = makeDemoScene({.textureSize = 16});
    scene.objects[2].mesh = 42;
    CHECK_THROWS_WITH(r.setScene(std::make_shared<const Scene>(scene)), Catch::Contains("checker"));
  }
  expectNoValidationMessages(*device);
}

TEST_CASE("a hand model from the exported glTF template draws the golden, a broken one is refused", "[renderer][hand]") {
  const auto dir = outputDir("renderer_hand_model");
  saveHandModel(makeHandMesh(), dir / "hand.glb", true);
  auto device = validatingDevice();
  {
    auto scene = std::make_shared<const Scene>(makeDemoScene({}));
    Renderer r(device);
    r.setScene(scene);
    r.setHandModel(loadHandModel(dir / "hand.glb"));
    OffscreenTarget target(device, kGoldenWidth, kGoldenHeight, 1);
    const FrameDesc frame = renderer::makeDemoFrame(*scene, kGoldenWidth, kGoldenHeight, false, false);
    REQUIRE(frame.hands.size() == 1);
    for (int i = 0; i < 3; ++i) REQUIRE(r.render(target, frame));
    checkGolden(target.readback(), "render_mono");
    HandMesh broken = makeHandMesh();
    broken.weights.resize(3);
    CHECK_THROWS_WITH(r.setHandModel(broken), Catch::Contains("hand model"));
    REQUIRE(r.render(target, frame));  // the previous model stays
  }
  expectNoValidationMessages(*device);
}

TEST_CASE("hand pose becomes joint spheres and bone capsules", "[renderer]") {
  std::vector<renderer::HandPrimitive> prims;
  renderer::appendHandPrimitives(HandPose{}, glm::vec4(1.0f), prims);
  CHECK(prims.empty());  // invalid pose: nothing drawn
  const HandPose pose = poseHand(glm::mat4(1.0f), {0, 0, 0, 0, 0});
  renderer::appendHandPrimitives(pose, glm::vec4(1.0f), prims);
  // 26 joints + 24 bones (every joint but palm and wrist hangs off a parent).
  REQUIRE(prims.size() == 50);
  int spheres = 0;
  for (const auto& p : prims) {
    if (p.a_world == p.b_world) ++spheres;
    CHECK(p.radius_m > 0.0f);
  }
  CHECK(spheres == 26);
}

TEST_CASE("device creation hooks and adopted devices render", "[renderer]") {
  int instanceCalls = 0, deviceCalls = 0;
  renderer::DeviceOptions options;
  options.validate = true;
  // What OpenXR's XR_KHR_vulkan_enable2 does: the runtime performs the creation calls.
  options.hooks.createInstance = [&](const VkInstanceCreateInfo& info) {
    ++instanceCalls;
    VkInstance instance = VK_NULL_HANDLE;
    VT_VK(vkCreateInstance(&info, nullptr, &instance));
    return instance;
  };
  options.hooks.createDevice = [&](VkPhysicalDevice physical, const VkDeviceCreateInfo& info) {
    ++deviceCalls;
    VkDevice device = VK_NULL_HANDLE;
    VT_VK(vkCreateDevice(physical, &info, nullptr, &device));
    return device;
  };
  auto owner = Device::create(options);
  CHECK(instanceCalls == 1);
  CHECK(deviceCalls == 1);
  {
    auto adopted = Device::adopt({owner->instance(), owner->physicalDevice(), owner->device(), owner->queueFamily(), 0});
    CHECK(adopted->description() == owner->description());
    Renderer r(adopted);
    OffscreenTarget target(adopted, 8, 8);
    REQUIRE(r.render(target, clearOnlyFrame({0.0f, 0.0f, 0.0f, 1.0f})));
    CHECK(target.readback().at(4, 4, 0) == 0);
  }  // the adopted wrapper must not destroy the owner's device
  owner->waitIdle();
  expectNoValidationMessages(*owner);
}

TEST_CASE("vulkan results are checked with the call and the result name", "[renderer]") {
  CHECK(std::string(renderer::resultName(VK_ERROR_DEVICE_LOST)) == "VK_ERROR_DEVICE_LOST");
  CHECK_NOTHROW(VT_VK(VK_SUCCESS));
  CHECK_NOTHROW(VT_VK(VK_SUBOPTIMAL_KHR));
  CHECK_THROWS_WITH(VT_VK(VK_ERROR_OUT_OF_DATE_KHR),
                    Catch::Contains("VK_ERROR_OUT_OF_DATE_KHR") && Catch::Contains("renderer_tests.cpp"));
}

TEST_CASE("multiview and per-view stereo agree", "[renderer]") {
  // Far enough that no triangle needs clipping (Mesa 22 lavapipe's multiview mishandles clipped
  // triangles in view 1; Device::multiviewReliable() routes it to per-view passes).
  Scene scene = makeDemoScene({.textureSize = 64});
  scene.camera.distance_m = 3.0f;
  auto shared = std::make_shared<const Scene>(scene);
  FrameDesc frame = renderer::makeDemoFrame(scene, 96, 54, true, true);  // the hand casts its shadow
  frame.contacts = {{{-0.09f, 0.006f, 0.0f}, {0.0f, 1.0f, 0.0f}, 1.0f}};
  auto device = validatingDevice();
  std::vector<Image8> results[2];
  const renderer::StereoMode modes[2] = {renderer::StereoMode::Multiview, renderer::StereoMode::PerView};
  for (int m = 0; m < 2; ++m) {
    Renderer r(device, {.stereo = modes[m]});
    CHECK(r.usesMultiview() == (m == 0));
    r.setScene(shared);
    OffscreenTarget target(device, 96, 54, 2);
    REQUIRE(r.render(target, frame));
    results[m] = {target.readback(0), target.readback(1)};
  }
  for (int eye = 0; eye < 2; ++eye) {
    INFO("eye " << eye);
    CHECK(results[0][std::size_t(eye)].pixels == results[1][std::size_t(eye)].pixels);
  }
  CHECK(results[1][0].pixels != results[1][1].pixels);
  expectNoValidationMessages(*device);
}

TEST_CASE("steady-state frames build no GPU objects", "[renderer]") {
  auto device = validatingDevice();
  {
    auto scene = std::make_shared<const Scene>(makeDemoScene({.textureSize = 32}));
    Renderer r(device);
    r.setScene(scene);
    OffscreenTarget mono(device, 32, 18, 1);
    OffscreenTarget stereo(device, 32, 18, 2);
    const FrameDesc monoFrame = renderer::makeDemoFrame(*scene, 32, 18, false, true);
    const FrameDesc stereoFrame = renderer::makeDemoFrame(*scene, 32, 18, true, false);
    REQUIRE(r.render(mono, monoFrame));
    REQUIRE(r.render(stereo, stereoFrame));
    const std::uint64_t builds = r.resourceBuilds();
    CHECK(builds >= 2);  // at least one framebuffer set per target
    for (int i = 0; i < 10; ++i) {
      REQUIRE(r.render(i % 2 ? mono : stereo, i % 2 ? monoFrame : stereoFrame));
    }
    CHECK(r.resourceBuilds() == builds);
    OffscreenTarget another(device, 16, 8, 1);
    REQUIRE(r.render(another, renderer::makeDemoFrame(*scene, 16, 8, false, false)));
    CHECK(r.resourceBuilds() == builds + 1);  // a new target: its framebuffers, same pipelines
  }
  expectNoValidationMessages(*device);
}
