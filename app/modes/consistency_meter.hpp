#pragma once
// The paper's claim measured in the running program: for each displayed frame, the contact
// each fingertip shows (the drawn hand, at the frame's display time) against what the
// actuators play at that same moment (the tick whose frame reaches the felt output then,
// counting that output's declared latency). Per finger: spatial offset on the surface (mm) and
// temporal offset (ms, the felt hand's time minus the drawn hand's: positive = touch leads
// sight); over the ticks: the share of moving in-contact ticks that repeat the previous contact
// point and the longest such frozen run; at each stop of the drawn hand: how long and how far
// the felt contact went on. Fed on the main thread by the touch pipeline; allocation happens
// only when the session is made (bounded rings) and in report().
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "vt/haptics/haptic_loop.hpp"

namespace vt::app {

/// One displayed frame: where each contact point of the hand was drawn.
struct DrawnFrame {
  std::int64_t display_t_ns = 0;  // when it is shown (predicted or measured display time)
  std::int64_t hand_t_ns = 0;     // the time of the hand it shows
  std::array<glm::vec3, haptics::kMaxContactPoints> tip_m{};  // contact-sphere centres, world
};

/// Percentiles of one offset.
struct OffsetStats {
  double p50 = 0.0, p99 = 0.0, max = 0.0;  // of |offset|
  double signedP99 = 0.0;                  // of the offset itself (ms: positive = touch leads sight)
  std::uint64_t count = 0;
};

struct FingerConsistency {
  std::string name;
  OffsetStats offset_mm, offset_ms;
  std::uint64_t movingContactTicks = 0, frozenTicks = 0;
  double frozenRunMax_ms = 0.0;
};

/// What the meter measured so far.
struct ConsistencyReport {
  std::vector<FingerConsistency> fingers;  // one per contact point
  OffsetStats offset_mm, offset_ms;        // every finger together
  std::uint64_t framesCompared = 0;        // displayed frames matched with a felt tick
  double displayRate_hz = 0.0;             // displayed frames per second (over the session)
  std::uint64_t movingContactTicks = 0;    // ticks in contact while the hand moved
  std::uint64_t frozenTicks = 0;           // ... that repeated the previous contact point
  double frozenMovingPct = 0.0;
  double frozenRunMax_ms = 0.0;            // longest run of repeated contact points while moving
  std::uint64_t stops = 0;                 // stops of the drawn hand in contact
  double stopOvershoot_ms = 0.0, stopOvershoot_mm = 0.0;  // worst felt motion after a drawn stop
  std::int64_t feltLatency_ns = 0;         // the felt output's latency counted

  /// "offset p99 0.31 mm 1.2 ms, frozen 0.00 % (max 0 ms), stop overshoot 3 ms 0.02 mm".
  std::string line() const;
};

class ConsistencyMeter {
 public:
  /// Traces older than this are forgotten (a frame must be matched within it).
  static constexpr std::int64_t kWindow_ns = 2'000'000'000;

  /// `contacts`: the loop's contact points (names and count); `tickPeriod_ns`: the loop's period.
  ConsistencyMeter(const std::vector<haptics::ContactPoint>& contacts, std::int64_t tickPeriod_ns);

  /// The latency of the output whose felt moment is compared (the pipeline's felt sinks).
  void setFeltLatency(std::int64_t latency_ns) { m_feltLatency_ns = latency_ns; }
  /// An input pose (the hand as the input read it), in stamp order: says when the hand moves.
  void addInput(const HandPose& pose);
  /// One contact point's state in one tick, in tick order (the loop's traces).
  void addTrace(const haptics::ContactTrace& trace);
  /// A displayed frame; compared once the felt tick for its display time has arrived.
  void addFrame(const DrawnFrame& frame);
  /// Forgets everything measured (the loop restarted with new settings).
  void reset();
  ConsistencyReport report() const;

 private:
  struct Felt {
    std::int64_t t_ns = 0, hand_t_ns = 0;
    glm::vec3 tip_m{0.0f}, normal{0.0f, 1.0f, 0.0f};
    bool inContact = false;
  };
  // A stop of the hand (seen in the input), followed until the felt contact has been watched
  // for kStopFollow after the first frame that shows the hand stopped.
  struct Stop {
    std::int64_t hand_t_ns = 0;     // when the input hand stopped (0: no stop followed)
    std::int64_t display_t_ns = 0;  // the first frame showing it stopped (0: not shown yet)
    glm::vec3 rest_m{0.0f};         // where the input tip rests
    bool started = false;
  };
  /// The input tip slid along the surface (normal `normal`) over the window ending at hand_t:
  /// pressing into it or lifting off is not sliding.
  bool moving(std::int64_t hand_t_ns, std::size_t contact, glm::vec3 normal = {0.0f, 1.0f, 0.0f}) const;
  const Felt* feltAt(std::size_t contact, std::int64_t t_ns) const;
  void compare(const DrawnFrame& frame);
  void followStops(const haptics::ContactTrace& trace);
  void noteInputStop(std::size_t contact, std::int64_t t_ns);
  const glm::vec3* inputTipAt(std::int64_t t_ns, std::size_t contact) const;

  std::vector<haptics::ContactPoint> m_contacts;
  std::int64_t m_period_ns;
  std::int64_t m_feltLatency_ns = 0;
  // Felt ticks per contact, a ring of kWindow_ns worth.
  std::vector<std::vector<Felt>> m_felt;
  std::vector<std::size_t> m_feltCount;
  // Input tips per contact: a ring of recent stamps and positions.
  static constexpr std::size_t kInputs = 4096;
  std::vector<std::int64_t> m_inputT;
  std::vector<std::array<glm::vec3, haptics::kMaxContactPoints>> m_inputTip;
  std::size_t m_inputCount = 0;
  std::vector<DrawnFrame> m_pending;  // frames waiting for their felt tick
  std::vector<bool> m_inputMoving;  // per contact: the input tip moved since its last stop
  // Results.
  std::vector<std::vector<float>> m_mm, m_ms;  // per contact, bounded (the newest kKept)
  std::vector<float> m_mmMax, m_msMax;
  std::vector<std::uint64_t> m_compared;
  std::uint64_t m_frames = 0;
  std::uint64_t m_framesShown = 0;
  std::int64_t m_firstShown_ns = 0, m_lastShown_ns = 0;
  std::uint64_t m_moving = 0, m_frozen = 0;
  std::vector<std::int64_t> m_frozenSince;  // per contact: start of the current frozen run (0: none)
  std::vector<std::int64_t> m_frozenRunMax_ns;
  std::vector<std::uint64_t> m_movingPer, m_frozenPer;
  std::vector<Stop> m_stops;  // per contact: the stop being followed
  std::uint64_t m_stopCount = 0;
  double m_overshoot_ms = 0.0, m_overshoot_mm = 0.0;
};

}  // namespace vt::app
