#include "vt/net/video_stream.hpp"

#include <algorithm>
#include <cstring>

#include "vt/core/error.hpp"

namespace vt::net {

namespace {

// Frame ids wrap; "newer" is serial-number arithmetic over half the id space.
bool newer(std::uint32_t a, std::uint32_t b) noexcept { return std::int32_t(a - b) > 0; }

}  // namespace

std::size_t videoFragmentCount(std::size_t bytes) noexcept { return (bytes + kMaxVideoData - 1) / kMaxVideoData; }

bool fragmentVideoFrame(std::span<const std::uint8_t> jpeg, std::uint32_t frameId, int width, int height,
                        const std::function<void(const Video&)>& emit) {
  if (jpeg.empty() || jpeg.size() > kMaxVideoFrameBytes || width < 1 || width > 65535 || height < 1 || height > 65535)
    return false;
  Video message;
  message.frameId = frameId;
  message.width = std::uint16_t(width);
  message.height = std::uint16_t(height);
  message.format = VideoFormat::Jpeg;
  message.fragmentCount = std::uint16_t(videoFragmentCount(jpeg.size()));
  for (std::size_t i = 0; i < message.fragmentCount; ++i) {
    const std::size_t offset = i * kMaxVideoData;
    message.fragmentIndex = std::uint16_t(i);
    message.dataSize = std::uint16_t(std::min(kMaxVideoData, jpeg.size() - offset));
    std::memcpy(message.data.data(), jpeg.data() + offset, message.dataSize);
    emit(message);
  }
  return true;
}

VideoReassembler::VideoReassembler(VideoReassemblerConfig config) : m_config(config) {
  if (m_config.maxFrameBytes < 1 || m_config.maxFrameBytes > kMaxVideoFrameBytes)
    fail("video reassembler: maxFrameBytes ", m_config.maxFrameBytes, " not in 1..", kMaxVideoFrameBytes);
  if (m_config.framesInFlight < 1 || m_config.framesInFlight > 16)
    fail("video reassembler: framesInFlight ", m_config.framesInFlight, " not in 1..16");
  m_maxFragments = videoFragmentCount(m_config.maxFrameBytes);
  m_slots.resize(std::size_t(m_config.framesInFlight));
  for (Slot& slot : m_slots) {
    slot.have.assign(m_maxFragments, 0);
    slot.bytes.reserve(m_maxFragments * kMaxVideoData);
  }
  m_completed.jpeg.reserve(m_maxFragments * kMaxVideoData);
}

VideoStats VideoReassembler::stats() const noexcept {
  return {m_completedCount.load(), m_abandoned.load(), m_rejected.load()};
}

void VideoReassembler::release(Slot& slot, bool abandoned) noexcept {
  if (abandoned) m_abandoned.fetch_add(1, std::memory_order_relaxed);
  std::fill(slot.have.begin(), slot.have.begin() + slot.fragmentCount, std::uint8_t(0));
  slot.used = false;
  slot.received = 0;
}

VideoReassembler::Slot* VideoReassembler::slotFor(const Video& fragment) noexcept {
  Slot* free = nullptr;
  Slot* oldest = nullptr;
  for (Slot& slot : m_slots) {
    if (!slot.used) {
      if (!free) free = &slot;
    } else if (slot.frameId == fragment.frameId) {
      return &slot;
    } else if (!oldest || newer(oldest->frameId, slot.frameId)) {
      oldest = &slot;
    }
  }
  // A frame no newer than the last one completed would never be shown.
  if (m_haveCompleted && !newer(fragment.frameId, m_lastCompleted)) return nullptr;
  const std::size_t minBytes = std::size_t(fragment.fragmentCount - 1) * kMaxVideoData + 1;
  if (fragment.fragmentCount > m_maxFragments || minBytes > m_config.maxFrameBytes) return nullptr;
  Slot* slot = free;
  if (!slot) {  // every slot busy: the oldest frame in flight gives way, unless this one is older still
    if (newer(oldest->frameId, fragment.frameId)) return nullptr;
    release(*oldest, true);
    slot = oldest;
  }
  slot->used = true;
  slot->frameId = fragment.frameId;
  slot->width = fragment.width;
  slot->height = fragment.height;
  slot->fragmentCount = fragment.fragmentCount;
  slot->received = 0;
  slot->lastSize = 0;
  slot->bytes.resize(std::size_t(fragment.fragmentCount) * kMaxVideoData);  // within the reserved capacity
  return slot;
}

bool VideoReassembler::push(const Video& fragment) noexcept {
  const auto reject = [this] {
    m_rejected.fetch_add(1, std::memory_order_relaxed);
    return false;
  };
  const bool last = fragment.fragmentIndex + 1 == fragment.fragmentCount;
  if (fragment.format != VideoFormat::Jpeg || fragment.width == 0 || fragment.height == 0 ||
      fragment.fragmentIndex >= fragment.fragmentCount || fragment.dataSize == 0 || fragment.dataSize > kMaxVideoData ||
      (!last && fragment.dataSize != kMaxVideoData))
    return reject();
  Slot* slot = slotFor(fragment);
  if (!slot) return reject();
  if (slot->width != fragment.width || slot->height != fragment.height || slot->fragmentCount != fragment.fragmentCount ||
      slot->have[fragment.fragmentIndex])
    return reject();
  const std::size_t offset = std::size_t(fragment.fragmentIndex) * kMaxVideoData;
  if (last && offset + fragment.dataSize > m_config.maxFrameBytes) return reject();
  std::memcpy(slot->bytes.data() + offset, fragment.data.data(), fragment.dataSize);
  slot->have[fragment.fragmentIndex] = 1;
  if (last) slot->lastSize = fragment.dataSize;
  if (++slot->received < slot->fragmentCount) return false;

  slot->bytes.resize(std::size_t(slot->fragmentCount - 1) * kMaxVideoData + slot->lastSize);
  std::swap(m_completed.jpeg, slot->bytes);
  m_completed.frameId = slot->frameId;
  m_completed.width = slot->width;
  m_completed.height = slot->height;
  m_haveCompleted = true;
  m_lastCompleted = slot->frameId;
  m_completedCount.fetch_add(1, std::memory_order_relaxed);
  release(*slot, false);
  for (Slot& other : m_slots)
    if (other.used && !newer(other.frameId, m_lastCompleted)) release(other, true);
  return true;
}

LatestVideoFrame::LatestVideoFrame() {
  // Buffers circulate between here and the reassembler: keep them all full-sized.
  m_frame.jpeg.reserve(videoFragmentCount(kMaxVideoFrameBytes) * kMaxVideoData);
}

void LatestVideoFrame::publish(VideoFrame& frame) noexcept {
  std::lock_guard lock(m_mutex);
  std::swap(m_frame, frame);
  m_version.fetch_add(1, std::memory_order_release);
}

bool LatestVideoFrame::readNewer(VideoFrame& out, std::uint64_t& version) const {
  std::lock_guard lock(m_mutex);
  const std::uint64_t current = m_version.load(std::memory_order_relaxed);
  if (current == version) return false;
  out.frameId = m_frame.frameId;
  out.width = m_frame.width;
  out.height = m_frame.height;
  out.jpeg.assign(m_frame.jpeg.begin(), m_frame.jpeg.end());
  version = current;
  return true;
}

}  // namespace vt::net
