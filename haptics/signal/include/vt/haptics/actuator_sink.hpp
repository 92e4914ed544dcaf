#pragma once
// One way to attach an output. Every consumer of actuator frames (the glove, an audio
// interface, OSC, the XR controllers, the recorders, the network stream, the UI) is an
// ActuatorSink that says which thread feeds it, how late it plays what it is given and how it
// goes silent; the touch pipeline (app/modes/touch_pipeline) is the one place sinks are attached.
// A frame source (the haptic loop's thread, a client's network playout) writes realtime sinks'
// ports through a FrameFanout without waiting; the main thread delivers to the others.
#include <array>
#include <cstdint>
#include <string>

#include "vt/core/latest_value.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/haptics/actuator_frame.hpp"

namespace vt::haptics {

/// Which thread hands a sink its frames.
enum class SinkThread : std::uint8_t {
  Realtime,  // the frame source's own thread pushes into the sink's port; a device thread consumes
  Main,      // the main (UI) thread delivers every frame in order, then flushes once per drain
};

/// Where a realtime sink takes its frames; the frame source is the only producer.
struct SinkPort {
  SpscRing<ActuatorFrame>* ring = nullptr;        // every frame, in order (waveform outputs)
  LatestValue<ActuatorFrame>* mailbox = nullptr;  // the newest frame (level outputs)

  SinkPort() = default;
  SinkPort(SpscRing<ActuatorFrame>& r) : ring(&r) {}         // NOLINT: a ring is a port
  SinkPort(LatestValue<ActuatorFrame>& m) : mailbox(&m) {}   // NOLINT: a mailbox is a port
};

/// An output of actuator frames (thread rules per member).
class ActuatorSink {
 public:
  virtual ~ActuatorSink() = default;
  /// Short name for the HUD and reports: "glove sim", "audio:default", "osc://host:9000", "xr", ...
  virtual std::string name() const = 0;
  virtual SinkThread thread() const = 0;
  /// Realtime sinks: the port the frame source writes (valid until stop()). Setup thread.
  virtual SinkPort port() { return {}; }
  /// Main sinks: one frame, every frame in order. Main thread.
  virtual void deliver(const ActuatorFrame& /*frame*/) {}
  /// Main sinks: after each drain (e.g. the XR controllers send once per display frame). Main thread.
  virtual void flush() {}
  /// From a frame's production (ActuatorFrame::t_ns) to when its actuators play it, in ns: the
  /// report period, the device buffer, the display frame, the network playout. Any thread.
  virtual std::int64_t latency_ns() const = 0;
  /// True when a person feels its output (the consistency meter and the loop's timing count
  /// these); false for recorders and the UI.
  virtual bool felt() const { return true; }
  /// One status line for the HUD and --json ("" when there is nothing to say). Main thread.
  virtual std::string statusLine() const { return {}; }
  /// Drives every actuator to zero and stops (threads joined, files put in place; throws
  /// vt::Error when a file cannot be finished). Idempotent. Main thread.
  virtual void stop() = 0;
};

/// The realtime ports one frame source writes. Ports are added on the setup thread before the
/// source runs; emit() is lock-free and allocation-free (safe on the haptic thread).
class FrameFanout {
 public:
  static constexpr int kMaxPorts = 8;

  /// Throws vt::Error when the port is empty or all kMaxPorts are taken. Setup thread.
  void add(SinkPort port);
  /// Every port gets the frame (a full ring refuses and counts it). Frame source's thread.
  void emit(const ActuatorFrame& frame) const noexcept {
    for (int i = 0; i < m_count; ++i) {
      const SinkPort& p = m_ports[std::size_t(i)];
      if (p.ring) p.ring->push(frame);
      else p.mailbox->publish(frame);
    }
  }
  int size() const noexcept { return m_count; }

 private:
  std::array<SinkPort, kMaxPorts> m_ports{};
  int m_count = 0;
};

}  // namespace vt::haptics
