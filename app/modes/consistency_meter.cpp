#include "modes/consistency_meter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "modes/hand_control.hpp"

namespace vt::app {
namespace {

constexpr std::size_t kKept = 1 << 16;              // offsets kept per finger for percentiles
constexpr std::int64_t kMotionWindow_ns = 10'000'000;  // "moving": the input tip moved over this
constexpr float kMoving_m = 100e-6f;                 // ... more than this (10 mm/s)
constexpr float kStill_m = 1e-6f;                    // a contact point "repeats" within this (1 mm/s)
constexpr std::int64_t kStopFollow_ns = 300'000'000;  // felt motion is followed this long after a stop
constexpr std::int64_t kStill_ns = 100'000'000;       // a stop: the input tip stays within kStopStill_m of a point this long
constexpr float kStopStill_m = 20e-6f;
constexpr float kStopped_m = 50e-6f;  // after a stop, texture "continues" while the felt contact is farther than this

double percentile(std::vector<float> v, double p) {
  if (v.empty()) return 0.0;
  const auto k = std::size_t(std::min(double(v.size() - 1), std::floor(p * double(v.size()))));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return double(v[k]);
}

void keep(std::vector<float>& values, std::uint64_t index, float value) {
  if (values.size() < kKept) values.push_back(value);
  else values[index % kKept] = value;
}

OffsetStats stats(const std::vector<float>& values, double max, std::uint64_t count) {
  std::vector<float> v = values;
  for (float& x : v) x = std::abs(x);
  return {percentile(v, 0.5), percentile(v, 0.99), max, percentile(values, 0.99), count};
}

// The component of `d` along the surface (its normal removed).
glm::vec3 alongSurface(glm::vec3 d, glm::vec3 normal) { return d - normal * glm::dot(d, normal); }

}  // namespace

std::string ConsistencyReport::line() const {
  char text[240];
  std::snprintf(text, sizeof text,
                "offset p99 %.2f mm %.1f ms (%llu frames), frozen %.2f %% of %llu moving ticks (longest %.0f ms), "
                "stop overshoot %.0f ms %.2f mm (%llu stops)",
                offset_mm.p99, offset_ms.p99, (unsigned long long)framesCompared, frozenMovingPct,
                (unsigned long long)movingContactTicks, frozenRunMax_ms, stopOvershoot_ms, stopOvershoot_mm,
                (unsigned long long)stops);
  return text;
}

ConsistencyMeter::ConsistencyMeter(const std::vector<haptics::ContactPoint>& contacts, std::int64_t tickPeriod_ns)
    : m_contacts(contacts), m_period_ns(std::max<std::int64_t>(1, tickPeriod_ns)) {
  const std::size_t n = m_contacts.size();
  m_felt.assign(n, std::vector<Felt>(std::size_t(kWindow_ns / m_period_ns) + 1));
  m_inputT.assign(kInputs, 0);
  m_inputTip.assign(kInputs, {});
  m_shownDisplayT.assign(kShown, 0);
  m_shownHandT.assign(kShown, 0);
  reset();
}

void ConsistencyMeter::reset() {
  const std::size_t n = m_contacts.size();
  m_feltCount.assign(n, 0);
  m_inputCount = 0;
  m_pending.clear();
  m_inputMoving.assign(n, false);
  m_mm.assign(n, {});
  m_ms.assign(n, {});
  m_mmMax.assign(n, 0.0f);
  m_msMax.assign(n, 0.0f);
  m_compared.assign(n, 0);
  m_frames = m_moving = m_frozen = m_framesShown = 0;
  m_firstShown_ns = m_lastShown_ns = 0;
  m_frozenSince.assign(n, 0);
  m_frozenRunMax_ns.assign(n, 0);
  m_movingPer.assign(n, 0);
  m_frozenPer.assign(n, 0);
  m_anchorT.assign(n, 0);
  m_anchorTip.assign(n, glm::vec3(0.0f));
  m_stops.assign(n, {});
  m_stopTotals = {};
}

void ConsistencyMeter::addInput(const HandPose& pose) {
  if (!pose.valid) return;
  const std::size_t slot = m_inputCount++ % kInputs;
  m_inputT[slot] = pose.t_ns;
  for (std::size_t c = 0; c < m_contacts.size(); ++c) {
    m_inputTip[slot][c] = pose.at(m_contacts[c].joint);
    noteInputStop(c, pose.t_ns, m_inputTip[slot][c]);
  }
}

const glm::vec3* ConsistencyMeter::inputTipAt(std::int64_t t_ns, std::size_t contact) const {
  // The newest input at or before t (inputs arrive in stamp order).
  const std::size_t n = std::min(m_inputCount, kInputs);
  for (std::size_t k = 1; k <= n; ++k) {
    const std::size_t slot = (m_inputCount - k) % kInputs;
    if (m_inputT[slot] <= t_ns) return &m_inputTip[slot][contact];
  }
  return nullptr;
}

void ConsistencyMeter::noteInputStop(std::size_t contact, std::int64_t t_ns, glm::vec3 tip) {
  // Open stops learn how long the hand rests: until an input leaves the rest point.
  for (Stop& stop : m_stops[contact]) {
    if (stop.hand_t_ns == 0 || stop.left) continue;
    if (glm::length(tip - stop.rest_m) > kStopStill_m) stop.left = true;
    else stop.restEnd_t_ns = t_ns;
  }
  // A stop: after sliding, every input for kStill_ns stays within kStopStill_m of one point (not
  // only the window's two ends: a reversal passes the same point on its way back).
  if (m_anchorT[contact] == 0 || glm::length(tip - m_anchorTip[contact]) > kStopStill_m) {
    m_anchorT[contact] = t_ns;
    m_anchorTip[contact] = tip;
  }
  if (m_inputMoving[contact] && t_ns - m_anchorT[contact] >= kStill_ns) {
    m_inputMoving[contact] = false;
    // A free slot, or the oldest stop judged now with the felt ticks there are.
    auto& stops = m_stops[contact];
    Stop* slot = &*std::min_element(stops.begin(), stops.end(),
                                    [](const Stop& a, const Stop& b) { return a.hand_t_ns < b.hand_t_ns; });
    if (slot->hand_t_ns != 0 && slot->display_t_ns != 0) m_stopTotals.add(stopMotion(contact, *slot));
    *slot = Stop{m_anchorT[contact], firstShowing(m_anchorT[contact]), t_ns, m_anchorTip[contact], false};
  } else if (moving(t_ns, contact)) {
    m_inputMoving[contact] = true;
  }
}

bool ConsistencyMeter::moving(std::int64_t hand_t_ns, std::size_t contact, glm::vec3 normal) const {
  const glm::vec3* now = inputTipAt(hand_t_ns, contact);
  const glm::vec3* before = inputTipAt(hand_t_ns - kMotionWindow_ns, contact);
  return now && before && glm::length(alongSurface(*now - *before, normal)) > kMoving_m;
}

void ConsistencyMeter::addTrace(const haptics::ContactTrace& trace) {
  const std::size_t c = trace.contact;
  if (c >= m_contacts.size()) return;
  std::vector<Felt>& ring = m_felt[c];
  const Felt* previous = m_feltCount[c] ? &ring[(m_feltCount[c] - 1) % ring.size()] : nullptr;
  // A repeat: in contact on consecutive ticks, the same point, while the input hand moved.
  if (trace.inContact && previous && previous->inContact && moving(trace.pose_t_ns, c, trace.normal)) {
    ++m_moving;
    ++m_movingPer[c];
    if (glm::length(trace.tip_m - previous->tip_m) <= kStill_m) {
      ++m_frozen;
      ++m_frozenPer[c];
      if (m_frozenSince[c] == 0) m_frozenSince[c] = previous->t_ns;
      m_frozenRunMax_ns[c] = std::max(m_frozenRunMax_ns[c], trace.t_ns - m_frozenSince[c]);
    } else {
      m_frozenSince[c] = 0;
    }
  } else {
    m_frozenSince[c] = 0;
  }
  ring[m_feltCount[c]++ % ring.size()] = {trace.t_ns, trace.pose_t_ns, trace.tip_m, trace.normal, trace.inContact};
  closeStops(trace);
  // Frames whose felt tick (display time less the output's latency) has now arrived.
  if (c + 1 == m_contacts.size()) {
    std::erase_if(m_pending, [&](const DrawnFrame& frame) {
      if (frame.display_t_ns - m_feltLatency_ns > trace.t_ns) return false;
      compare(frame);
      return true;
    });
  }
}

const ConsistencyMeter::Felt* ConsistencyMeter::feltAt(std::size_t contact, std::int64_t t_ns) const {
  const std::vector<Felt>& ring = m_felt[contact];
  const std::size_t n = std::min(m_feltCount[contact], ring.size());
  const Felt* best = nullptr;
  for (std::size_t k = 1; k <= n; ++k) {
    const Felt& f = ring[(m_feltCount[contact] - k) % ring.size()];
    if (!best || std::llabs(f.t_ns - t_ns) < std::llabs(best->t_ns - t_ns)) best = &f;
    if (f.t_ns < t_ns - m_period_ns) break;  // older ticks only get farther
  }
  return best && std::llabs(best->t_ns - t_ns) <= m_period_ns ? best : nullptr;
}

std::int64_t ConsistencyMeter::firstShowing(std::int64_t hand_t_ns) const {
  std::int64_t display_ns = 0;
  for (std::size_t k = 1; k <= std::min<std::size_t>(m_framesShown, kShown); ++k) {  // newest first
    const std::size_t slot = (m_framesShown - k) % kShown;
    if (m_shownHandT[slot] < hand_t_ns) break;
    display_ns = m_shownDisplayT[slot];
  }
  return display_ns;
}

void ConsistencyMeter::addFrame(const DrawnFrame& frame) {
  m_shownDisplayT[m_framesShown % kShown] = frame.display_t_ns;
  m_shownHandT[m_framesShown % kShown] = frame.hand_t_ns;
  if (m_framesShown++ == 0) m_firstShown_ns = frame.display_t_ns;
  m_lastShown_ns = frame.display_t_ns;
  for (auto& stops : m_stops)
    for (Stop& stop : stops)
      if (stop.hand_t_ns != 0 && stop.display_t_ns == 0 && frame.hand_t_ns >= stop.hand_t_ns) stop.display_t_ns = frame.display_t_ns;
  if (m_pending.size() >= 256) m_pending.erase(m_pending.begin());  // no ticks at all: the loop is stopped
  m_pending.push_back(frame);
}

void ConsistencyMeter::compare(const DrawnFrame& frame) {
  const std::int64_t tick_ns = frame.display_t_ns - m_feltLatency_ns;
  bool any = false;
  for (std::size_t c = 0; c < m_contacts.size(); ++c) {
    const Felt* felt = feltAt(c, tick_ns);
    if (!felt || !felt->inContact) continue;
    const float mm = glm::length(alongSurface(felt->tip_m - frame.tip_m[c], felt->normal)) * 1000.0f;
    const auto ms = float(double(felt->hand_t_ns - frame.hand_t_ns) * 1e-6);
    keep(m_mm[c], m_compared[c], mm);
    keep(m_ms[c], m_compared[c], ms);
    m_mmMax[c] = std::max(m_mmMax[c], mm);
    m_msMax[c] = std::max(m_msMax[c], std::abs(ms));
    ++m_compared[c];
    any = true;
  }
  if (any) ++m_frames;
}

void ConsistencyMeter::closeStops(const haptics::ContactTrace& trace) {
  // A stop is judged once the felt side is past it: its follow window is over, the finger
  // lifted, or the ticks render the hand after it moved on.
  const std::int64_t felt_ns = trace.t_ns + m_feltLatency_ns;  // when this tick is felt
  for (Stop& stop : m_stops[trace.contact]) {
    if (stop.hand_t_ns == 0 || stop.display_t_ns == 0 || felt_ns < stop.display_t_ns) continue;
    const bool over = felt_ns - stop.display_t_ns > kStopFollow_ns || !trace.inContact ||
                      (stop.left && trace.pose_t_ns > stop.restEnd_t_ns);
    if (!over) continue;
    m_stopTotals.add(stopMotion(trace.contact, stop));
    stop = Stop{};
  }
}

ConsistencyMeter::StopMotion ConsistencyMeter::stopMotion(std::size_t contact, const Stop& stop) const {
  // After the first frame that shows the hand stopped, the felt contact should not move: how
  // long it still moves (felt moments after that frame) and how far. Only ticks rendering the
  // hand while it rested count: once it moves on (at the first input away from the rest point,
  // or between that input and the one before), felt motion is the next move, not a run-on.
  StopMotion motion;
  const std::vector<Felt>& ring = m_felt[contact];
  for (std::size_t k = std::min(m_feltCount[contact], ring.size()); k >= 1; --k) {  // oldest first
    const Felt& f = ring[(m_feltCount[contact] - k) % ring.size()];
    const std::int64_t felt_ns = f.t_ns + m_feltLatency_ns;
    if (felt_ns < stop.display_t_ns) continue;
    if (felt_ns - stop.display_t_ns > kStopFollow_ns || !f.inContact || f.hand_t_ns > stop.restEnd_t_ns) break;
    motion.followed = true;
    // Still moving: farther from where the hand rests than kStopped_m (a twentieth of a 1 mm texture).
    const float away = glm::length(alongSurface(f.tip_m - stop.rest_m, f.normal));
    if (away > kStopped_m) {
      motion.ms = std::max(motion.ms, double(felt_ns - stop.display_t_ns) * 1e-6);
      motion.mm = std::max(motion.mm, double(away) * 1000.0);
    }
  }
  return motion;
}

void ConsistencyMeter::StopTotals::add(const StopMotion& motion) {
  if (!motion.followed) return;
  ++count;
  ms = std::max(ms, motion.ms);
  mm = std::max(mm, motion.mm);
}

ConsistencyReport ConsistencyMeter::report() const {
  ConsistencyReport r;
  std::vector<float> allMm, allMs;
  double maxMm = 0.0, maxMs = 0.0;
  std::uint64_t all = 0;
  for (std::size_t c = 0; c < m_contacts.size(); ++c) {
    FingerConsistency f;
    f.name = fingerName(fingerOfTip(m_contacts[c].joint));
    f.offset_mm = stats(m_mm[c], m_mmMax[c], m_compared[c]);
    f.offset_ms = stats(m_ms[c], m_msMax[c], m_compared[c]);
    allMm.insert(allMm.end(), m_mm[c].begin(), m_mm[c].end());
    allMs.insert(allMs.end(), m_ms[c].begin(), m_ms[c].end());
    maxMm = std::max(maxMm, double(m_mmMax[c]));
    maxMs = std::max(maxMs, double(m_msMax[c]));
    all += m_compared[c];
    f.movingContactTicks = m_movingPer[c];
    f.frozenTicks = m_frozenPer[c];
    f.frozenRunMax_ms = double(m_frozenRunMax_ns[c]) * 1e-6;
    r.frozenRunMax_ms = std::max(r.frozenRunMax_ms, f.frozenRunMax_ms);
    r.fingers.push_back(std::move(f));
  }
  r.offset_mm = stats(allMm, maxMm, all);
  r.offset_ms = stats(allMs, maxMs, all);
  r.framesCompared = m_frames;
  if (m_framesShown > 1 && m_lastShown_ns > m_firstShown_ns)
    r.displayRate_hz = double(m_framesShown - 1) / (double(m_lastShown_ns - m_firstShown_ns) * 1e-9);
  r.movingContactTicks = m_moving;
  r.frozenTicks = m_frozen;
  r.frozenMovingPct = m_moving ? 100.0 * double(m_frozen) / double(m_moving) : 0.0;
  // Stops the felt side has not passed yet count with the ticks there are.
  StopTotals stops = m_stopTotals;
  for (std::size_t c = 0; c < m_contacts.size(); ++c)
    for (const Stop& stop : m_stops[c])
      if (stop.hand_t_ns != 0 && stop.display_t_ns != 0) stops.add(stopMotion(c, stop));
  r.stops = stops.count;
  r.stopOvershoot_ms = stops.ms;
  r.stopOvershoot_mm = stops.mm;
  r.feltLatency_ns = m_feltLatency_ns;
  return r;
}

}  // namespace vt::app
