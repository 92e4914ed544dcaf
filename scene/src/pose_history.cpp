#include "vt/scene/pose_history.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vt {
namespace {

// A pause longer than this between two poses starts a new segment: the hand that reappears is
// not swept from where it vanished.
constexpr std::int64_t kGap_ns = 500'000'000;
// The mean interval follows the recent poses (exponential average weight of the newest).
constexpr double kIntervalWeight = 0.1;
// Prediction reaches two pose intervals plus this past the newest pose (see PoseSamplingConfig).
constexpr std::int64_t kPredictionSlack_ns = 20'000'000;
// Prediction's velocity spans at least this long, found among this many newest poses (else it holds).
constexpr std::int64_t kMinVelocitySpan_ns = 500'000;
constexpr std::uint64_t kVelocitySearch = 8;

float maxJointDistance(const HandPose& a, const HandPose& b) noexcept {
  float most = 0.0f;
  for (std::size_t j = 0; j < std::size_t(kHandJointCount); ++j) most = std::max(most, glm::length(a.position[j] - b.position[j]));
  return most;
}

}  // namespace

const char* poseSamplingName(PoseSampling mode) noexcept {
  switch (mode) {
    case PoseSampling::Latest: return "latest";
    case PoseSampling::Interpolate: return "interpolate";
    case PoseSampling::Predict: return "predict";
  }
  return "?";
}

bool parsePoseSampling(const char* text, PoseSampling& out) noexcept {
  for (PoseSampling mode : {PoseSampling::Latest, PoseSampling::Interpolate, PoseSampling::Predict}) {
    if (std::strcmp(text, poseSamplingName(mode)) == 0) {
      out = mode;
      return true;
    }
  }
  return false;
}

HandPose blendPoses(const HandPose& a, const HandPose& b, double s) noexcept {
  HandPose out = a;
  const auto f = float(s);
  for (std::size_t j = 0; j < std::size_t(kHandJointCount); ++j) {
    out.position[j] = a.position[j] + (b.position[j] - a.position[j]) * f;
    out.orientation[j] = glm::normalize(glm::slerp(a.orientation[j], b.orientation[j], f));
    out.radius_m[j] = std::max(0.0f, a.radius_m[j] + (b.radius_m[j] - a.radius_m[j]) * f);
  }
  return out;
}

bool PoseHistory::publish(const HandPose& pose, bool jump) noexcept {
  if (m_haveLast && pose.t_ns < m_last.t_ns) {
    m_rejected.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  if (m_haveLast) {
    const std::int64_t dt_ns = pose.t_ns - m_last.t_ns;
    const float moved_m = maxJointDistance(m_last, pose);
    const bool teleport = jump || !pose.valid || !m_last.valid || dt_ns > kGap_ns || moved_m > kTeleportDistance_m ||
                          (dt_ns > 0 && double(moved_m) / (double(dt_ns) * 1e-9) > double(kTeleportSpeed_mps));
    if (teleport) {
      ++m_segment;
    } else if (dt_ns > 0) {
      m_intervalAverage_ns = m_intervalAverage_ns == 0.0 ? double(dt_ns)
                                                         : m_intervalAverage_ns + kIntervalWeight * (double(dt_ns) - m_intervalAverage_ns);
      m_interval_ns.store(std::int64_t(m_intervalAverage_ns), std::memory_order_relaxed);
    }
  }
  const std::uint64_t index = m_count.load(std::memory_order_relaxed);
  m_slots[index % kCapacity].publish(Entry{index, m_segment, pose});
  m_count.store(index + 1, std::memory_order_release);
  m_last = pose;
  m_haveLast = true;
  return true;
}

bool PoseHistory::read(std::uint64_t index, Entry& out) const noexcept {
  return m_slots[index % kCapacity].read(out) && out.index == index;
}

bool PoseHistory::at(std::uint64_t index, HandPose& out, std::uint32_t& segment) const noexcept {
  Entry entry;
  if (index >= m_count.load(std::memory_order_acquire) || !read(index, entry)) return false;
  out = entry.pose;
  segment = entry.segment;
  return true;
}

bool PoseHistory::newest(HandPose& out) const noexcept {
  Entry entry;
  for (;;) {
    const std::uint64_t count = m_count.load(std::memory_order_acquire);
    if (count == 0) return false;
    if (read(count - 1, entry)) break;  // else overwritten while read: take the newer newest
  }
  out = entry.pose;
  return true;
}

PoseSample PoseHistory::sample(std::int64_t t_ns, const PoseSamplingConfig& config) const noexcept {
  PoseSample result;
  result.pose.t_ns = t_ns;
  Entry newest;
  std::uint64_t count = 0;
  for (;;) {
    count = m_count.load(std::memory_order_acquire);
    if (count == 0) return result;
    if (read(count - 1, newest)) break;
  }
  result.newest_t_ns = newest.pose.t_ns;
  result.segment = newest.segment;
  if (config.timeout_ns > 0 && t_ns - newest.pose.t_ns > config.timeout_ns) return result;  // no hand
  if (config.mode == PoseSampling::Latest) {
    result.pose = newest.pose;
    return result;
  }
  const std::int64_t q_ns = t_ns;

  if (q_ns >= newest.pose.t_ns) {
    // Past the newest pose: hold it (Interpolate), or continue its velocity for a bounded time.
    result.pose = newest.pose;
    result.extrapolated = true;
    // The velocity is taken over at least kMinVelocitySpan_ns: two stamps microseconds apart
    // (a source publishing twice for one frame) would make a velocity of their rounding noise,
    // which the extrapolation multiplies by its reach (a 0.1 um difference 1 us apart, predicted
    // 2 ms ahead: 0.2 mm).
    Entry previous;
    bool havePrevious = false;
    if (config.mode == PoseSampling::Predict && newest.pose.valid) {
      for (std::uint64_t back = 2; back <= std::min<std::uint64_t>(count, kVelocitySearch); ++back) {
        if (!read(count - back, previous) || previous.segment != newest.segment) break;
        if (previous.pose.t_ns <= newest.pose.t_ns - kMinVelocitySpan_ns) {
          havePrevious = true;
          break;
        }
      }
    }
    if (havePrevious) {
      const std::int64_t span_ns = newest.pose.t_ns - previous.pose.t_ns;
      const std::int64_t horizon_ns = std::min(config.maxPrediction_ns, 2 * interval_ns() + kPredictionSlack_ns);
      const std::int64_t ahead_ns = std::min(q_ns - newest.pose.t_ns, horizon_ns);
      result.pose = blendPoses(previous.pose, newest.pose, 1.0 + double(ahead_ns) / double(span_ns));
    }
    result.pose.t_ns = q_ns;
    return result;
  }

  // Galloping search back from the newest (q is usually within a pose or two of it), then
  // binary search, for the newest entry stamped at or before q among those still stored (the
  // oldest slot is left alone: the writer may be overwriting it).
  const std::uint64_t oldest = count > kCapacity - 1 ? count - (kCapacity - 1) : 0;
  std::uint64_t hi = count - 1;  // invariant: entry hi is stamped after q
  std::uint64_t lo = hi;
  Entry before;
  for (std::uint64_t step = 1;; step *= 2) {
    lo = hi - std::min(step, hi - oldest);
    if (lo == hi) break;  // nothing older is stored
    if (!read(lo, before)) return result;  // the writer lapped this reader: no answer this time
    if (before.pose.t_ns <= q_ns) break;
    hi = lo;
  }
  if (lo == hi) {
    // Older than anything stored: the oldest pose, held.
    if (!read(hi, before)) return result;
    result.pose = before.pose;
    result.segment = before.segment;
    result.pose.t_ns = q_ns;
    return result;
  }
  Entry probe;
  while (hi - lo > 1) {
    const std::uint64_t mid = lo + (hi - lo) / 2;
    if (!read(mid, probe)) return result;
    if (probe.pose.t_ns <= q_ns) {
      lo = mid;
      before = probe;
    } else {
      hi = mid;
    }
  }
  Entry after;
  if (!read(hi, after)) return result;
  result.segment = before.segment;
  if (after.segment != before.segment) {
    result.pose = before.pose;  // never blend across a teleport: the older pose holds until the jump
  } else {
    const double s = double(q_ns - before.pose.t_ns) / double(after.pose.t_ns - before.pose.t_ns);
    result.pose = blendPoses(before.pose, after.pose, s);
  }
  result.pose.t_ns = q_ns;
  return result;
}

}  // namespace vt
