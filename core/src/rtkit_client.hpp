#pragma once
// A minimal RealtimeKit client (org.freedesktop.RealtimeKit1 on the D-Bus system bus).
#include <string>

#include <sys/types.h>

namespace vt::detail {

/// Asks RealtimeKit to make thread `tid` of this process real-time at `priority` (capped at the
/// daemon's MaxRealtimePriority; RLIMIT_RTTIME is lowered to its RTTimeUSecMax first, which it
/// requires). Returns the empty string on success, else why it failed. Blocks up to ~1 s.
std::string rtkitMakeThreadRealtime(pid_t tid, int priority);

}  // namespace vt::detail
