// The external-image target (OpenXR swapchain images): images created and owned outside the
// renderer, drawn with the same passes, must give the same pictures as the offscreen target.
#include <catch2/catch.hpp>

#include <utility>

#include "image_compare.hpp"
#include "render_fixture.hpp"
#include "vt/core/error.hpp"
#include "vt/renderer/demo_frame.hpp"
#include "vt/renderer/external_target.hpp"
#include "vt/renderer/readback.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/renderer/vk_check.hpp"

using namespace vt;
using namespace vt::test;
using namespace vt::renderer;

namespace {

/// What an OpenXR runtime would hand out: a few colour (or depth) images with their own memory.
struct FakeSwapchain {
  VkDevice device = VK_NULL_HANDLE;
  std::vector<VkImage> images;
  std::vector<VkDeviceMemory> memory;

  FakeSwapchain(const Device& dev, std::uint32_t count, VkExtent2D extent, std::uint32_t layers,
                VkFormat format = VK_FORMAT_R8G8B8A8_SRGB,
                VkImageUsageFlags usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                          VK_IMAGE_USAGE_SAMPLED_BIT)
      : device(dev.device()) {
    for (std::uint32_t i = 0; i < count; ++i) {
      VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
      info.imageType = VK_IMAGE_TYPE_2D;
      info.format = format;
      info.extent = {extent.width, extent.height, 1};
      info.mipLevels = 1;
      info.arrayLayers = layers;
      info.samples = VK_SAMPLE_COUNT_1_BIT;
      info.tiling = VK_IMAGE_TILING_OPTIMAL;
      info.usage = usage;
      VkImage image = VK_NULL_HANDLE;
      VT_VK(vkCreateImage(device, &info, nullptr, &image));
      images.push_back(image);
      VkMemoryRequirements req;
      vkGetImageMemoryRequirements(device, image, &req);
      VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
      alloc.allocationSize = req.size;
      alloc.memoryTypeIndex = dev.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
      VkDeviceMemory mem = VK_NULL_HANDLE;
      VT_VK(vkAllocateMemory(device, &alloc, nullptr, &mem));
      memory.push_back(mem);
      VT_VK(vkBindImageMemory(device, image, mem, 0));
    }
  }
  ~FakeSwapchain() {
    for (VkImage i : images) vkDestroyImage(device, i, nullptr);
    for (VkDeviceMemory m : memory) vkFreeMemory(device, m, nullptr);
  }
};

}  // namespace

TEST_CASE("external images render the stereo goldens", "[renderer][golden]") {
  auto device = validatingDevice();
  {
    const VkExtent2D extent{kGoldenWidth, kGoldenHeight};
    FakeSwapchain swapchain(*device, 3, extent, 2);
    auto scene = std::make_shared<const Scene>(makeDemoScene());
    Renderer r(device);
    r.setScene(scene);
    ExternalTarget target(device, {swapchain.images, VK_FORMAT_R8G8B8A8_SRGB, extent, 2});
    const FrameDesc frame = makeDemoFrame(*scene, kGoldenWidth, kGoldenHeight, true, false);
    // As an XR frame loop: the runtime picks the image each frame.
    for (std::uint32_t index : {0u, 2u, 1u}) {
      target.setCurrentImage(index);
      REQUIRE(r.render(target, frame));
    }
    r.waitIdle();
    for (std::uint32_t eye = 0; eye < 2; ++eye) {
      const Image8 image = readImage(*device, swapchain.images[1], VK_FORMAT_R8G8B8A8_SRGB, extent, eye,
                                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
      checkGolden(image, eye == 0 ? "render_stereo_left" : "render_stereo_right");
    }
    CHECK_THROWS_WITH(target.setCurrentImage(3), Catch::Contains("image 3 of 3"));
  }
  expectNoValidationMessages(*device);
}

TEST_CASE("external target rejects bad image descriptions", "[renderer]") {
  auto device = validatingDevice();
  CHECK_THROWS_WITH(ExternalTarget(device, {{}, VK_FORMAT_R8G8B8A8_SRGB, {8, 8}, 1}), Catch::Contains("no images"));
  FakeSwapchain swapchain(*device, 1, {8, 8}, 1);
  CHECK_THROWS_WITH(ExternalTarget(device, {swapchain.images, VK_FORMAT_R8G8B8A8_SRGB, {0, 8}, 1}),
                    Catch::Contains("zero extent"));
  CHECK_THROWS_WITH(ExternalTarget(device, {swapchain.images, VK_FORMAT_R8G8B8A8_SRGB, {8, 8}, 3}),
                    Catch::Contains("3 layers"));
  expectNoValidationMessages(*device);
}

TEST_CASE("external depth images receive the stereo scene depth and the colour stays golden", "[renderer][golden]") {
  auto device = validatingDevice();
  {
    const VkExtent2D extent{kGoldenWidth, kGoldenHeight};
    VkFormat depthFormat = VK_FORMAT_UNDEFINED;
    for (VkFormat f : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D16_UNORM}) {
      if (depthFormat == VK_FORMAT_UNDEFINED && supportsExternalDepth(*device, f)) depthFormat = f;
    }
    REQUIRE(depthFormat != VK_FORMAT_UNDEFINED);
    CHECK_FALSE(supportsExternalDepth(*device, VK_FORMAT_R8G8B8A8_SRGB));
    FakeSwapchain color(*device, 3, extent, 2);
    FakeSwapchain depth(*device, 2, extent, 2, depthFormat,
                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    auto scene = std::make_shared<const Scene>(makeDemoScene());
    Renderer r(device);
    r.setScene(scene);
    ExternalImages desc{color.images, VK_FORMAT_R8G8B8A8_SRGB, extent, 2};
    desc.depthImages = depth.images;
    desc.depthFormat = depthFormat;
    ExternalTarget target(device, desc);
    const FrameDesc frame = makeDemoFrame(*scene, kGoldenWidth, kGoldenHeight, true, false);
    // The colour and depth swapchains hand out their indices independently.
    std::uint64_t builds = 0;
    for (auto [c, d] : {std::pair{0u, 1u}, {2u, 0u}, {1u, 1u}}) {
      target.setCurrentImage(c);
      target.setCurrentDepthImage(d);
      REQUIRE(r.render(target, frame));
      if (builds == 0) builds = r.resourceBuilds();
    }
    CHECK(r.resourceBuilds() == builds);  // all framebuffers were made with the first frame
    r.waitIdle();
    for (std::uint32_t eye = 0; eye < 2; ++eye) {
      INFO("eye " << eye);
      const Image8 image = readImage(*device, color.images[1], VK_FORMAT_R8G8B8A8_SRGB, extent, eye,
                                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
      checkGolden(image, eye == 0 ? "render_stereo_left" : "render_stereo_right");
      // Stored depth, left as OpenXR expects: cleared to 1 where the sky shows, the scene
      // nearer; the view's near/far planes map to 0/1.
      const ImageF z = readDepth(*device, depth.images[1], depthFormat, extent, eye,
                                 VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
      const CameraView& view = frame.views[eye];
      std::size_t cleared = 0, drawn = 0;
      for (std::size_t i = 0; i < z.pixels.size(); ++i) {
        const float d = z.pixels[i];
        if (d == 1.0f) {
          ++cleared;
          continue;
        }
        ++drawn;
        // Eye-space distance from window depth (CameraView::projection).
        const float distance_m = view.near_m * view.far_m / (view.far_m - d * (view.far_m - view.near_m));
        if (!(distance_m > view.near_m && distance_m < 5.0f)) FAIL("pixel " << i << " depth " << d << " = " << distance_m << " m");
      }
      CHECK(drawn > z.pixels.size() / 2);
      CHECK(cleared > 0);
      // Near the bottom the table edge is closer than at the image centre.
      CHECK(z.at(int(extent.width / 2), int(extent.height) - 4) < z.at(int(extent.width / 2), int(extent.height / 2)));
      // The other depth image was drawn too, not only the last one.
      const ImageF other = readDepth(*device, depth.images[0], depthFormat, extent, eye,
                                     VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
      CHECK(other.pixels == z.pixels);
    }
    CHECK_THROWS_WITH(target.setCurrentDepthImage(2), Catch::Contains("depth image 2 of 2"));
  }
  expectNoValidationMessages(*device);
}

TEST_CASE("external target rejects depth images it cannot draw into", "[renderer]") {
  auto device = validatingDevice();
  FakeSwapchain color(*device, 1, {8, 8}, 1);
  FakeSwapchain notDepth(*device, 1, {8, 8}, 1);
  ExternalImages desc{color.images, VK_FORMAT_R8G8B8A8_SRGB, {8, 8}, 1};
  desc.depthImages = notDepth.images;
  desc.depthFormat = VK_FORMAT_R8G8B8A8_SRGB;
  CHECK_THROWS_WITH(ExternalTarget(device, desc), Catch::Contains("not usable as a depth attachment"));
  desc.depthImages = {VK_NULL_HANDLE};
  desc.depthFormat = VK_FORMAT_D16_UNORM;
  CHECK_THROWS_WITH(ExternalTarget(device, desc), Catch::Contains("null depth image"));
  expectNoValidationMessages(*device);
}
