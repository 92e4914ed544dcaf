#include "vt/haptics/actuator_sink.hpp"

#include "vt/core/error.hpp"

namespace vt::haptics {

void FrameFanout::add(SinkPort port) {
  if (!port.ring && !port.mailbox) fail("frame outputs: a realtime sink without a ring or mailbox");
  if (m_count == kMaxPorts) fail("frame outputs: more than ", kMaxPorts, " realtime sinks");
  m_ports[std::size_t(m_count++)] = port;
}

}  // namespace vt::haptics
