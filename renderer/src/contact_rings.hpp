#pragma once
// Contact markers (FrameDesc::contacts) drawn as rings lying on the touched surfaces: the ring
// pipeline and one host-visible instance buffer per frame slot (internal).
#include <cstdint>
#include <vector>

#include "gpu.hpp"
#include "vt/renderer/frame.hpp"

namespace vt::renderer {

/// Ring radius at intensity 0 and at intensity 1 (m): the ring grows with the touch.
inline constexpr float kRingRadiusMin_m = 0.012f;
inline constexpr float kRingRadiusMax_m = 0.03f;

/// The ring pipeline in `pass`: instanced strips, alpha-blended, depth test <=, no depth write.
VkPipeline createRingPipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass pass);

class ContactRings {
 public:
  ContactRings(const Device& dev, std::uint32_t slots);
  /// Writes the frame's markers (at most kMaxContactMarkers) into the slot's buffer.
  void upload(std::uint32_t slot, const std::vector<ContactMarker>& markers);
  /// Draws the slot's rings with `pipeline` (the frame set is bound); nothing without markers.
  void draw(VkCommandBuffer cmd, std::uint32_t slot, VkPipeline pipeline) const;

 private:
  std::vector<GpuBuffer> m_buffers;
  std::vector<std::uint32_t> m_counts;
};

}  // namespace vt::renderer
