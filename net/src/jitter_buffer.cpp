#include "vt/net/jitter_buffer.hpp"

#include <algorithm>

namespace vt::net {

void JitterBuffer::restart(const haptics::ActuatorFrame& frame, std::int64_t now_ns) noexcept {
  m_filled.fill(false);
  m_active = true;
  m_nextSequence = m_highestSequence = m_baseSequence = frame.sequence;
  m_baseArrival_ns = now_ns;
  m_offsetCount = m_offsetNext = 0;
  m_minOffset_ns = 0;
  m_schedule_ns = m_config.minDelay_ns;
  m_spanCount = m_spanNext = m_windowArrivals = 0;
  m_missingRun = 0;
}

void JitterBuffer::updateDelay(std::int64_t offset_ns) noexcept {
  m_offsets[std::size_t(m_offsetNext)] = offset_ns;
  m_offsetNext = (m_offsetNext + 1) % kWindow;
  m_offsetCount = std::min(m_offsetCount + 1, kWindow);
  // Baseline = earliest arrival in the window; the schedule covers the configured quantile of
  // the spread above it (the maximum by default: every recent arrival would have been on time).
  std::array<std::int64_t, kWindow> sorted{};
  std::copy_n(m_offsets.begin(), m_offsetCount, sorted.begin());
  std::sort(sorted.begin(), sorted.begin() + m_offsetCount);
  m_minOffset_ns = sorted[0];
  const std::int64_t spread = sorted[std::size_t((m_offsetCount - 1) * m_config.spreadPercent / 100)] - m_minOffset_ns;
  const std::int64_t need_ns = m_minOffset_ns + std::clamp(spread + m_config.minDelay_ns, m_config.minDelay_ns, m_config.maxDelay_ns);
  // Every move of the schedule moves when each frame is felt, which the client's hand lead can
  // only follow after the fact: it moves later at once (a late frame is worse), and earlier only
  // once the need of the last kSpans windows together lies below it, by at most kFall per
  // window (a larger step made the frames already in flight late).
  std::int64_t longNeed_ns = need_ns;
  for (int i = 0; i < m_spanCount; ++i) longNeed_ns = std::max(longNeed_ns, m_spanNeed[std::size_t(i)]);
  if (need_ns > m_schedule_ns) m_schedule_ns = need_ns;
  if (++m_windowArrivals >= kWindow) {
    if (m_spanCount == kSpans && longNeed_ns < m_schedule_ns) m_schedule_ns -= std::min(kFall_ns, m_schedule_ns - longNeed_ns);
    m_spanNeed[std::size_t(m_spanNext)] = need_ns;
    m_spanNext = (m_spanNext + 1) % kSpans;
    m_spanCount = std::min(m_spanCount + 1, kSpans);
    m_windowArrivals = 0;
  }
  m_stats.targetDelay_ns = m_schedule_ns - m_minOffset_ns;
}

std::int64_t JitterBuffer::dueOf(std::uint64_t sequence) const noexcept {
  const auto slots = std::int64_t(sequence - m_baseSequence);
  return m_baseArrival_ns + slots * m_config.period_ns + m_schedule_ns;
}

void JitterBuffer::push(const haptics::ActuatorFrame& frame, std::int64_t now_ns) noexcept {
  ++m_stats.received;
  if (!m_active) restart(frame, now_ns);
  const auto offsetOf = [&] {
    return now_ns - (m_baseArrival_ns + std::int64_t(frame.sequence - m_baseSequence) * m_config.period_ns);
  };
  if (frame.sequence < m_nextSequence) {
    // Already played or concealed; a far older one means the sender restarted.
    if (m_nextSequence - frame.sequence > std::uint64_t(kSlots)) {
      ++m_stats.resyncs;
      restart(frame, now_ns);
    } else {
      ++m_stats.late;
      updateDelay(offsetOf());  // late arrivals are exactly what the delay must learn from
      return;
    }
  } else if (frame.sequence - m_nextSequence >= std::uint64_t(kSlots)) {
    ++m_stats.resyncs;
    restart(frame, now_ns);
  }
  const std::size_t slot = frame.sequence % kSlots;
  if (m_filled[slot] && m_slots[slot].sequence == frame.sequence) {
    ++m_stats.duplicates;
    return;
  }
  if (frame.sequence < m_highestSequence) ++m_stats.reordered;
  m_highestSequence = std::max(m_highestSequence, frame.sequence);
  m_slots[slot] = frame;
  m_filled[slot] = true;
  updateDelay(offsetOf());
  m_stats.depth = countDepth();
  m_stats.maxDepth = std::max(m_stats.maxDepth, m_stats.depth);
}

std::int64_t JitterBuffer::nextDue_ns() const noexcept {
  return m_active ? dueOf(m_nextSequence) : std::numeric_limits<std::int64_t>::max();
}

int JitterBuffer::countDepth() const noexcept {
  int depth = 0;
  for (int i = 0; i < kSlots; ++i) {
    const std::size_t slot = std::size_t(i);
    depth += m_filled[slot] && m_slots[slot].sequence >= m_nextSequence ? 1 : 0;
  }
  return depth;
}

void JitterBuffer::conceal(haptics::ActuatorFrame& out) noexcept {
  const int hold = m_config.holdFrames, fade = std::max(m_config.fadeFrames, 1);
  out = m_haveLast ? m_last : haptics::ActuatorFrame{};
  out.pose_t_ns = 0;  // no pose behind it: sinks and latency statistics can tell
  // Gain at the end of the previous slot and of this one; ramped per sample (no click).
  const auto gainAfter = [&](int run) {
    if (run <= hold) return 1.0f;
    return std::max(0.0f, float(hold + fade - run) / float(fade));
  };
  const float g0 = gainAfter(m_missingRun - 1), g1 = gainAfter(m_missingRun);
  const int n = std::max<int>(out.blockLength, 1);
  for (int c = 0; c < haptics::kMaxActuators; ++c) {
    auto& block = out.block[std::size_t(c)];
    for (int i = 0; i < haptics::kMaxBlockSamples; ++i)
      block[std::size_t(i)] *= g0 + (g1 - g0) * float(i + 1) / float(n);
    out.intensity[std::size_t(c)] *= g1;
    if (g1 == 0.0f) block.fill(0.0f);
  }
}

bool JitterBuffer::pop(std::int64_t now_ns, haptics::ActuatorFrame& out, bool& concealed) noexcept {
  if (!m_active || now_ns < dueOf(m_nextSequence)) return false;
  const std::size_t slot = m_nextSequence % kSlots;
  if (m_filled[slot] && m_slots[slot].sequence == m_nextSequence) {
    out = m_slots[slot];
    m_filled[slot] = false;
    m_last = out;
    m_haveLast = true;
    m_stats.lost += std::uint64_t(m_missingRun);
    m_missingRun = 0;
    ++m_stats.played;
    concealed = false;
  } else {
    ++m_missingRun;
    conceal(out);
    out.sequence = m_nextSequence;
    ++m_stats.concealed;
    concealed = true;
    if (m_missingRun >= m_config.holdFrames + m_config.fadeFrames + m_config.idleFrames) {
      // The stream stopped: this silent frame is the last output until frames return.
      m_active = false;
      m_haveLast = false;
      m_missingRun = 0;
    }
  }
  ++m_nextSequence;
  m_stats.depth = countDepth();
  return true;
}

}  // namespace vt::net
