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
  // A stop of the hand (seen in the input): judged from the felt ticks kept in the ring once the
  // felt side is past it, so ticks the loop made before the input showed the stop count too.
  struct Stop {
    std::int64_t hand_t_ns = 0;     // when the input hand stopped (0: free slot)
    std::int64_t display_t_ns = 0;  // the first frame showing it stopped (0: not shown yet)
    std::int64_t restEnd_t_ns = 0;  // the newest input stamp still at rest
    glm::vec3 rest_m{0.0f};         // where the input tip rests
    bool left = false;              // an input after restEnd moved away: the rest is over
  };
  struct StopMotion {
    bool followed = false;  // at least one felt tick in contact while the hand rested
    double ms = 0.0, mm = 0.0;
  };
  struct StopTotals {
    std::uint64_t count = 0;  // stops followed
    double ms = 0.0, mm = 0.0;
    void add(const StopMotion& motion);
  };
  /// Stops of one contact still open (a new one may start before the felt side is past the last).
  static constexpr std::size_t kOpenStops = 4;
  /// The input tip slid along the surface (normal `normal`) over the window ending at hand_t:
  /// pressing into it or lifting off is not sliding.
  bool moving(std::int64_t hand_t_ns, std::size_t contact, glm::vec3 normal = {0.0f, 1.0f, 0.0f}) const;
  const Felt* feltAt(std::size_t contact, std::int64_t t_ns) const;
  void compare(const DrawnFrame& frame);
  void closeStops(const haptics::ContactTrace& trace);
  /// The felt contact's motion after the stop was shown: felt ticks from its display on, while in
  /// contact and while the input hand (at each tick's hand time) still rested there.
  StopMotion stopMotion(std::size_t contact, const Stop& stop) const;
  void noteInputStop(std::size_t contact, std::int64_t t_ns, glm::vec3 tip);
  const glm::vec3* inputTipAt(std::int64_t t_ns, std::size_t contact) const;
  /// The display time of the first kept frame showing the hand at or after hand_t (0: none yet).
  std::int64_t firstShowing(std::int64_t hand_t_ns) const;

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
  // Recent displayed frames (display and hand times), a ring: a stop the input shows only
  // kStill_ns later finds the first frame that showed it.
  static constexpr std::size_t kShown = 512;
  std::vector<std::int64_t> m_shownDisplayT, m_shownHandT;
  std::vector<bool> m_inputMoving;  // per contact: the input tip moved since its last stop
  // Per contact: the input tip has stayed within kStopStill_m of the anchor since its stamp.
  std::vector<std::int64_t> m_anchorT;
  std::vector<glm::vec3> m_anchorTip;
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
  std::vector<std::array<Stop, kOpenStops>> m_stops;  // per contact: stops not judged yet
  StopTotals m_stopTotals;  // of the stops judged
};

}  // namespace vt::app
