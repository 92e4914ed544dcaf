#pragma once
// Real-time scheduling for the threads whose wake-up time is the latency (haptic loop, the
// network threads of the tactile client and server). Best effort: without permission
// (root or CAP_SYS_NICE) the thread keeps normal scheduling and the caller reports that.

namespace vt {

/// Calling thread: SCHED_FIFO at `priority` (1..99). True when granted. Never throws.
bool requestRealtimePriority(int priority) noexcept;

}  // namespace vt
