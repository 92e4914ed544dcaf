#include "gpu.hpp"

#include <utility>

#include "vt/renderer/vk_check.hpp"

namespace vt::renderer {
namespace {

// Memory of a type with `properties` for what `req` asks, for a buffer or an image to bind.
VkDeviceMemory allocateFor(const Device& dev, const VkMemoryRequirements& req, VkMemoryPropertyFlags properties) {
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = dev.memoryType(req.memoryTypeBits, properties);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VT_VK(vkAllocateMemory(dev.device(), &alloc, nullptr, &memory));
  return memory;
}

}  // namespace

GpuBuffer::GpuBuffer(const Device& dev, VkDeviceSize bytes, VkBufferUsageFlags usage,
                     VkMemoryPropertyFlags properties)
    : device(dev.device()), size(bytes) {
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = bytes;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VT_VK(vkCreateBuffer(device, &info, nullptr, &buffer));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device, buffer, &req);
  memory = allocateFor(dev, req, properties);
  VT_VK(vkBindBufferMemory(device, buffer, memory, 0));
  if (properties & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) VT_VK(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped));
}

GpuBuffer& GpuBuffer::operator=(GpuBuffer&& other) noexcept {
  if (this != &other) {
    reset();
    device = std::exchange(other.device, VK_NULL_HANDLE);
    buffer = std::exchange(other.buffer, VK_NULL_HANDLE);
    memory = std::exchange(other.memory, VK_NULL_HANDLE);
    size = std::exchange(other.size, 0);
    mapped = std::exchange(other.mapped, nullptr);
  }
  return *this;
}

void GpuBuffer::reset() noexcept {
  if (buffer) vkDestroyBuffer(device, buffer, nullptr);
  if (memory) vkFreeMemory(device, memory, nullptr);  // unmaps implicitly
  buffer = VK_NULL_HANDLE;
  memory = VK_NULL_HANDLE;
  mapped = nullptr;
}

VkImageView createView(VkDevice device, VkImage image, VkFormat format, VkImageAspectFlags aspect,
                       std::uint32_t layers, std::uint32_t levels, bool arrayView, std::uint32_t baseLayer) {
  VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  info.image = image;
  info.viewType = arrayView ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
  info.format = format;
  info.subresourceRange = {aspect, 0, levels, baseLayer, layers};
  VkImageView view = VK_NULL_HANDLE;
  VT_VK(vkCreateImageView(device, &info, nullptr, &view));
  return view;
}

VkImageAspectFlags depthAspectOf(VkFormat format) noexcept {
  const bool stencil = format == VK_FORMAT_D24_UNORM_S8_UINT || format == VK_FORMAT_D32_SFLOAT_S8_UINT ||
                       format == VK_FORMAT_D16_UNORM_S8_UINT;
  return stencil ? VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT : VK_IMAGE_ASPECT_DEPTH_BIT;
}

GpuImage::GpuImage(const Device& dev, const ImageSpec& imageSpec, bool arrayView)
    : device(dev.device()), spec(imageSpec) {
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = spec.format;
  info.extent = {spec.extent.width, spec.extent.height, 1};
  info.mipLevels = spec.mipLevels;
  info.arrayLayers = spec.layers;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = spec.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VT_VK(vkCreateImage(device, &info, nullptr, &image));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device, image, &req);
  memory = allocateFor(dev, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  VT_VK(vkBindImageMemory(device, image, memory, 0));
  view = createView(device, image, spec.format, spec.aspect, spec.layers, spec.mipLevels, arrayView);
}

GpuImage& GpuImage::operator=(GpuImage&& other) noexcept {
  if (this != &other) {
    reset();
    device = std::exchange(other.device, VK_NULL_HANDLE);
    image = std::exchange(other.image, VK_NULL_HANDLE);
    memory = std::exchange(other.memory, VK_NULL_HANDLE);
    view = std::exchange(other.view, VK_NULL_HANDLE);
    spec = other.spec;
  }
  return *this;
}

void GpuImage::reset() noexcept {
  if (view) vkDestroyImageView(device, view, nullptr);
  if (image) vkDestroyImage(device, image, nullptr);
  if (memory) vkFreeMemory(device, memory, nullptr);
  view = VK_NULL_HANDLE;
  image = VK_NULL_HANDLE;
  memory = VK_NULL_HANDLE;
}

void submitOnce(const Device& dev, const std::function<void(VkCommandBuffer)>& record) {
  VkDevice device = dev.device();
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  poolInfo.queueFamilyIndex = dev.queueFamily();
  VkCommandPool pool = VK_NULL_HANDLE;
  VT_VK(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
  // The pool goes away on every exit path (a failed record throws).
  struct PoolGuard {
    VkDevice device;
    VkCommandPool pool;
    ~PoolGuard() { vkDestroyCommandPool(device, pool, nullptr); }
  } guard{device, pool};
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VT_VK(vkAllocateCommandBuffers(device, &alloc, &cmd));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VT_VK(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  VT_VK(vkEndCommandBuffer(cmd));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  VT_VK(vkQueueSubmit(dev.queue(), 1, &submit, VK_NULL_HANDLE));
  VT_VK(vkQueueWaitIdle(dev.queue()));
}

void transitionImage(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                     VkImageLayout to, std::uint32_t baseLevel, std::uint32_t levels, std::uint32_t layers) {
  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {aspect, baseLevel, levels, 0, layers};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &barrier);
}

}  // namespace vt::renderer
