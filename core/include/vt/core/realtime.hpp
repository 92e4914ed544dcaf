#pragma once
// Real-time scheduling for the threads whose wake-up time is the latency (haptic loop, device
// output writers, network threads). Best effort, in this order: SCHED_FIFO directly (root or
// CAP_SYS_NICE); else RealtimeKit over the D-Bus system bus, as PipeWire and PulseAudio do for
// desktop users; else normal scheduling. Every call also sets the thread's timer slack to the
// minimum and is recorded, so the HUD and --json can say what each thread was granted.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace vt {

/// How a thread got (or did not get) real-time scheduling.
enum class RealtimeMethod : std::uint8_t { None, SchedFifo, RealtimeKit };

/// What one requestRealtime call obtained for its thread.
struct RealtimeGrant {
  RealtimeMethod method = RealtimeMethod::None;
  int policy = 0;                  // SCHED_OTHER / SCHED_FIFO / SCHED_RR after the call
  int priority = 0;                // real-time priority after the call (0: none)
  std::int64_t timerSlack_ns = 0;  // the thread's timer slack after the call
  /// True when the thread now runs with a real-time policy.
  bool granted() const noexcept { return method != RealtimeMethod::None; }
};

/// One thread's grant as recorded for reports; `refusal` says why each method failed.
struct ThreadGrant {
  std::string thread;
  RealtimeGrant grant;
  std::string refusal;
};

/// Calling thread, at its start (it may block on D-Bus for up to ~1 s, allocates): asks for
/// real-time priority `priority` (1..99; RealtimeKit may cap it lower), sets the minimum timer
/// slack, and records the outcome under `thread` (replacing an earlier one of that name).
/// RealtimeKit requires RLIMIT_RTTIME, so on that path the process's limit is lowered to the
/// daemon's maximum (200 ms by default): a thread spinning that long without sleeping gets SIGXCPU.
/// Never throws.
RealtimeGrant requestRealtime(std::string_view thread, int priority) noexcept;

/// Any thread: every recorded grant, in the order the threads first asked.
std::vector<ThreadGrant> realtimeGrants();
/// Any thread: one line for the HUD, e.g. "haptic: SCHED_RR 20 via RealtimeKit, slack 0 ns".
std::string describeRealtimeGrants();
/// "none", "SCHED_FIFO" or "RealtimeKit".
std::string_view realtimeMethodName(RealtimeMethod method) noexcept;
/// "SCHED_OTHER", "SCHED_FIFO", "SCHED_RR", ... for a policy value.
std::string_view schedulingPolicyName(int policy) noexcept;

}  // namespace vt
