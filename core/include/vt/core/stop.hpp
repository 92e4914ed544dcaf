#pragma once
// The process's one stop request. SIGINT/SIGTERM (installStopSignals), the UI or a mode set it;
// every loop watches it (window, headset, client, server, acquisition) and every actuator
// output is held silent while it is set, so there is one shutdown path for every mode.
namespace vt {

/// Value of stopSignal() when the stop came from the program itself (UI, end of run).
inline constexpr int kStopByProgram = -1;

/// Asks every loop to end. Any thread, async-signal-safe.
void requestStop(int reason = kStopByProgram) noexcept;
/// Whether a stop was asked for. Any thread, async-signal-safe.
bool stopRequested() noexcept;
/// The signal that asked for the stop, kStopByProgram, or 0 when none. Any thread.
int stopSignal() noexcept;
/// Forgets the request (tests; an app that handled it and keeps running). Any thread.
void clearStop() noexcept;
/// SIGINT and SIGTERM request the stop; a second one ends the process at once (exit 128+n).
/// Main thread, once, before other threads start.
void installStopSignals();

}  // namespace vt
