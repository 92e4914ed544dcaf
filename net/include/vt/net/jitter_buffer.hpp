#pragma once
// Client-side playout of received actuator frames: a small adaptive jitter buffer with
// concealment. Frames carry consecutive sequence numbers, one per frame period; slot k plays at
// (earliest arrival baseline for k) + a delay that adapts to the recent arrival spread: later at
// once, earlier only in 1 ms steps once two 64-frame windows (0.5 - 0.75 s) needed less (each
// move shifts what is felt when). A
// missing slot repeats the last frame briefly, then fades it to zero, then plays silence; after
// a longer silence the stream is considered stopped. Output never stays non-zero once frames
// stop arriving. Concealment frames carry pose_t_ns = 0. Allocation-free after construction, single thread (the client's receiver).
#include <array>
#include <cstdint>
#include <limits>

#include "vt/haptics/actuator_frame.hpp"

namespace vt::net {

/// Playout and concealment settings (durations in ns).
struct JitterConfig {
  std::int64_t period_ns = 4'000'000;    // one frame's duration (blockLength / sampleRate)
  int holdFrames = 2;                    // repeat the last frame this many missing slots
  int fadeFrames = 3;                    // then ramp to zero over this many
  int idleFrames = 25;                   // silent slots after which playout stops
  std::int64_t minDelay_ns = 250'000;    // playout margin floor
  std::int64_t maxDelay_ns = 20'000'000;
  int spreadPercent = 100;               // arrival-spread percentile (over the last 64) covered
};

/// Counters; read on the receiver thread (the client copies them out for other threads).
struct JitterStats {
  std::uint64_t received = 0;    // frames pushed
  std::uint64_t played = 0;      // frames played on time
  std::uint64_t concealed = 0;   // slots filled by hold, fade or silence
  std::uint64_t lost = 0;        // slots missing while the stream continued
  std::uint64_t late = 0;        // frames that arrived after their slot was played
  std::uint64_t reordered = 0;   // frames older than one already received
  std::uint64_t duplicates = 0;
  std::uint64_t resyncs = 0;     // sequence jumps that restarted the schedule
  int depth = 0;                 // frames waiting right now
  int maxDepth = 0;
  std::int64_t targetDelay_ns = 0;
};

/// The playout buffer itself; one thread (the client's network thread) only.
class JitterBuffer {
 public:
  explicit JitterBuffer(const JitterConfig& config) noexcept : m_config(config) {}

  /// A frame arrived at now_ns.
  void push(const haptics::ActuatorFrame& frame, std::int64_t now_ns) noexcept;
  /// When the next slot is due; max() while nothing is playing.
  std::int64_t nextDue_ns() const noexcept;
  /// If a slot is due at now_ns, writes the frame to play (received or concealment) and
  /// returns true; `concealed` says which. Call until it returns false.
  bool pop(std::int64_t now_ns, haptics::ActuatorFrame& out, bool& concealed) noexcept;
  /// True while a stream is being played (including its concealment tail).
  bool active() const noexcept { return m_active; }
  const JitterStats& stats() const noexcept { return m_stats; }
  /// One frame's duration (the configured period).
  std::int64_t period_ns() const noexcept { return m_config.period_ns; }

 private:
  static constexpr int kSlots = 128;  // two whole datagrams of the longest blocks (kMaxTactileFrames)
  static constexpr int kWindow = 64;  // arrivals per estimate of the schedule's need
  static constexpr int kSpans = 2;    // the schedule moves earlier only below all these windows' needs
  static constexpr std::int64_t kFall_ns = 1'000'000;

  void restart(const haptics::ActuatorFrame& frame, std::int64_t now_ns) noexcept;
  void updateDelay(std::int64_t offset_ns) noexcept;
  std::int64_t dueOf(std::uint64_t sequence) const noexcept;
  void conceal(haptics::ActuatorFrame& out) noexcept;
  int countDepth() const noexcept;

  JitterConfig m_config;
  JitterStats m_stats;
  std::array<haptics::ActuatorFrame, kSlots> m_slots{};
  std::array<bool, kSlots> m_filled{};
  bool m_active = false;
  std::uint64_t m_nextSequence = 0;
  std::uint64_t m_highestSequence = 0;
  std::uint64_t m_baseSequence = 0;
  std::int64_t m_baseArrival_ns = 0;
  std::array<std::int64_t, kWindow> m_offsets{};
  int m_offsetCount = 0;
  int m_offsetNext = 0;
  std::int64_t m_minOffset_ns = 0;
  std::int64_t m_schedule_ns = 0;  // slot k plays at base + k periods + this
  std::array<std::int64_t, kSpans> m_spanNeed{};
  int m_spanCount = 0, m_spanNext = 0, m_windowArrivals = 0;
  haptics::ActuatorFrame m_last{};  // the last frame played, the source of concealment
  bool m_haveLast = false;
  int m_missingRun = 0;
};

}  // namespace vt::net
