#pragma once
// What the outputs with a writer thread of their own share (audio_output.cpp, osc_output.cpp).

namespace vt::haptics {

/// Their writer threads' priority: real time (a late write is a gap in the signal, and a lab
/// device listening at 1 kHz sees the loop's timing), but below the haptic loop (20): the
/// producer must never wait for one of its sinks.
inline constexpr int kOutputWriterPriority = 15;

}  // namespace vt::haptics
