#pragma once
// Where the hand is at any time t: a lock-free history of timestamped hand poses (one writer,
// any number of readers) that interpolates between the two poses bracketing t and, past the
// newest, extrapolates with a bounded constant-velocity model (Monado's relation history is
// the model). Every input path stamps its poses with the time they describe; every consumer
// samples at its own time: the renderer at display time, the haptic loop at each tick.
#include <atomic>
#include <cstdint>
#include <memory>

#include "vt/core/latest_value.hpp"
#include "vt/scene/hand.hpp"

namespace vt {

/// How a consumer turns the history into the pose at time t.
enum class PoseSampling : std::uint8_t {
  Latest,       // the newest pose whatever t (no timing model; the baseline)
  Interpolate,  // between the two poses around t; past the newest, hold it (the consumer
                // delays t by the poses' age so that it stays inside)
  Predict,      // interpolate inside, extrapolate (bounded) past the newest
};

/// "latest", "interpolate", "predict".
const char* poseSamplingName(PoseSampling mode) noexcept;
/// Parses a name above; false when it is none of them.
bool parsePoseSampling(const char* text, PoseSampling& out) noexcept;

/// How far a consumer trusts the history.
struct PoseSamplingConfig {
  PoseSampling mode = PoseSampling::Predict;
  /// No pose newer than t - timeout: there is no hand (the loop goes silent). At most kMaxTimeout_ns.
  std::int64_t timeout_ns = 100'000'000;
  static constexpr std::int64_t kMaxTimeout_ns = 10'000'000'000;
  /// Extrapolate at most this far past the newest pose (and at most two pose intervals plus
  /// 20 ms, so a fast source that stalls is not extrapolated for long), then hold.
  std::int64_t maxPrediction_ns = 100'000'000;
};

/// The hand at one asked time.
struct PoseSample {
  HandPose pose;                 // pose.t_ns = the asked time; pose.valid = false: no hand
  std::int64_t newest_t_ns = 0;  // stamp of the newest pose in the history
  std::uint32_t segment = 0;     // changes across a teleport: never sweep between segments
  bool extrapolated = false;     // t lay past the newest pose (Predict) or was held there
};

/// Lock-free single-writer history of hand poses. publish(): one writer thread. sample(),
/// newest(), counters: any thread, without locks or allocation (safe on the haptic thread).
class PoseHistory {
 public:
  /// Poses kept: 4 s at 1 kHz (the desktop's input rate), so a consumer aligned to a slow
  /// display's lag (hundreds of ms on a software renderer) still finds the poses around its time,
  /// and a recorder reading behind the writer keeps every pose while its thread (the render
  /// thread, drawing a frame on a loaded CPU) is away for up to that long.
  static constexpr std::size_t kCapacity = 4096;
  /// Two poses farther apart than this (any joint, per second of their stamps) are a teleport.
  static constexpr float kTeleportSpeed_mps = 4.0f;
  /// A jump of this size is a teleport whatever the time between the poses.
  static constexpr float kTeleportDistance_m = 0.25f;

  /// Appends a pose stamped with the time it describes (pose.t_ns, on the consumers' clock).
  /// Refused (false, counted) when older than the newest. `jump`: the source moved the hand on
  /// purpose (reset, re-centre): never interpolated or swept across. Writer thread only.
  bool publish(const HandPose& pose, bool jump = false) noexcept;

  /// The hand at time t_ns (see PoseSampling). Any thread; never blocks or allocates.
  PoseSample sample(std::int64_t t_ns, const PoseSamplingConfig& config) const noexcept;
  /// The newest pose (false when none yet). Any thread.
  bool newest(HandPose& out) const noexcept;
  /// The index-th pose ever accepted (0 = first) and its segment, while still stored (false
  /// once overwritten: recorders read behind the writer). Any thread.
  bool at(std::uint64_t index, HandPose& out, std::uint32_t& segment) const noexcept;

  /// Poses accepted so far. Any thread.
  std::uint64_t published() const noexcept { return m_count.load(std::memory_order_acquire); }
  /// Poses refused for an older stamp than the newest. Any thread.
  std::uint64_t rejected() const noexcept { return m_rejected.load(std::memory_order_relaxed); }
  /// Mean interval between recent pose stamps (0 before two poses). Any thread.
  std::int64_t interval_ns() const noexcept { return m_interval_ns.load(std::memory_order_relaxed); }

 private:
  struct Entry {
    std::uint64_t index = 0;    // position in the stream: detects a slot overwritten while read
    std::uint32_t segment = 0;
    HandPose pose;
  };
  bool read(std::uint64_t index, Entry& out) const noexcept;

  // On the heap (3.5 MB): histories are members and locals of threads with ordinary stacks.
  std::unique_ptr<LatestValue<Entry>[]> m_slots = std::make_unique<LatestValue<Entry>[]>(kCapacity);
  std::atomic<std::uint64_t> m_count{0};
  std::atomic<std::uint64_t> m_rejected{0};
  std::atomic<std::int64_t> m_interval_ns{0};
  // Writer-only state.
  HandPose m_last;
  bool m_haveLast = false;
  std::uint32_t m_segment = 0;
  double m_intervalAverage_ns = 0.0;
};

/// Joint-wise blend of two poses: positions and radii linearly, orientations by slerp; `s`
/// outside 0..1 extrapolates. The result's t_ns and validity are a's.
HandPose blendPoses(const HandPose& a, const HandPose& b, double s) noexcept;

}  // namespace vt
