#pragma once
// The optional server -> client video stream: compressed frames (JPEG) split into Video
// datagrams and put back together. Every fragment but the last carries exactly kMaxVideoData
// bytes, so fragment i sits at offset i * kMaxVideoData and a frame needs no per-fragment
// buffers. The reassembler keeps a few frames in flight in memory fixed at construction,
// tolerates loss and reordering (a lost fragment costs only its frame) and rejects and
// counts inconsistent fragments.
#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <span>
#include <vector>

#include "vt/net/protocol.hpp"

namespace vt::net {

/// Largest compressed frame either side sends or accepts (a 480x480 JPEG is ~20-60 KiB).
inline constexpr std::size_t kMaxVideoFrameBytes = 512u << 10;

/// One compressed frame with its size in pixels.
struct VideoFrame {
  std::uint32_t frameId = 0;
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> jpeg;
};

/// Fragments needed for a frame of `bytes` bytes.
std::size_t videoFragmentCount(std::size_t bytes) noexcept;

/// Splits `jpeg` into Video messages handed one by one to `emit` (the same object, refilled).
/// False (nothing emitted) when the frame is empty, over kMaxVideoFrameBytes, or its size is
/// not 1..65535 pixels a side. Any thread.
bool fragmentVideoFrame(std::span<const std::uint8_t> jpeg, std::uint32_t frameId, int width, int height,
                        const std::function<void(const Video&)>& emit);

/// Reassembler settings.
struct VideoReassemblerConfig {
  std::size_t maxFrameBytes = kMaxVideoFrameBytes;
  int framesInFlight = 3;  // incomplete frames kept; the oldest is abandoned for a new one
};

/// Reassembler counters; a snapshot is safe from any thread.
struct VideoStats {
  std::uint64_t completed = 0;
  std::uint64_t abandoned = 0;  // incomplete frames given up (a fragment lost, or overtaken)
  std::uint64_t rejected = 0;   // fragments refused: inconsistent, duplicate, too large, stale
};

/// Puts frames back together from fragments in any order. One thread pushes (the network
/// thread); stats() from any thread. All buffers are allocated at construction.
class VideoReassembler {
 public:
  /// Throws vt::Error for a limit above kMaxVideoFrameBytes or framesInFlight outside 1..16.
  explicit VideoReassembler(VideoReassemblerConfig config = {});

  /// Takes one fragment. True when it completed a frame: the frame is then in completed()
  /// until the next push. Incomplete frames older than a completed one are abandoned.
  bool push(const Video& fragment) noexcept;
  /// The frame the last successful push completed (its buffer may be swapped out).
  VideoFrame& completed() noexcept { return m_completed; }
  VideoStats stats() const noexcept;

 private:
  struct Slot {
    bool used = false;
    std::uint32_t frameId = 0;
    std::uint16_t width = 0, height = 0, fragmentCount = 0;
    std::size_t received = 0;
    std::size_t lastSize = 0;
    std::vector<std::uint8_t> have;  // per fragment index: 0/1
    std::vector<std::uint8_t> bytes;
  };
  Slot* slotFor(const Video& fragment) noexcept;
  void release(Slot& slot, bool abandoned) noexcept;

  VideoReassemblerConfig m_config;
  std::size_t m_maxFragments = 0;
  std::vector<Slot> m_slots;
  VideoFrame m_completed;
  bool m_haveCompleted = false;
  std::uint32_t m_lastCompleted = 0;
  std::atomic<std::uint64_t> m_completedCount{0}, m_abandoned{0}, m_rejected{0};
};

/// The newest complete frame, handed from the network thread to a viewer. Both sides hold the
/// lock only for a buffer swap or one frame copy. Any thread.
class LatestVideoFrame {
 public:
  LatestVideoFrame();
  /// Network thread: swaps `frame` in (its buffer comes back holding an older frame's).
  void publish(VideoFrame& frame) noexcept;
  /// Viewer: copies the newest frame into `out` when it is newer than `version` (then updates
  /// it). False when nothing newer arrived.
  bool readNewer(VideoFrame& out, std::uint64_t& version) const;
  /// Frames published so far.
  std::uint64_t version() const noexcept { return m_version.load(std::memory_order_acquire); }

 private:
  mutable std::mutex m_mutex;
  VideoFrame m_frame;
  std::atomic<std::uint64_t> m_version{0};
};

}  // namespace vt::net
