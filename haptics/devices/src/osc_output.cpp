#include "vt/haptics/devices/osc_output.hpp"

#include <lo/lo.h>
#include <netdb.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <string>

#include "vt/core/error.hpp"

namespace vt::haptics {
namespace {

constexpr std::int64_t kPoll_ns = 500'000;  // the writer's wake-up period while frames are awaited

}  // namespace

OscOutputConfig parseOscUrl(std::string_view url, OscOutputConfig config) {
  constexpr std::string_view kScheme = "osc://";
  if (url.substr(0, kScheme.size()) != kScheme) fail("--output '", url, "': expected osc://HOST:PORT");
  std::string_view rest = url.substr(kScheme.size());
  if (const std::size_t q = rest.find('?'); q != std::string_view::npos) {
    if (rest.substr(q + 1) != "blocks") fail("--output '", url, "': unknown option '", rest.substr(q + 1), "' (only ?blocks)");
    config.blocks = true;
    rest = rest.substr(0, q);
  }
  const std::size_t colon = rest.rfind(':');
  if (colon == std::string_view::npos || colon == 0) fail("--output '", url, "': expected osc://HOST:PORT");
  std::string_view host = rest.substr(0, colon);
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);  // IPv6
  const std::string_view port = rest.substr(colon + 1);
  int value = 0;
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (ec != std::errc() || end != port.data() + port.size() || value < 1 || value > 65535)
    fail("--output '", url, "': port '", port, "' is not 1..65535");
  config.host = std::string(host);
  config.port = std::string(port);
  return config;
}

struct OscOutput::Target {
  lo_address address = nullptr;
  std::array<std::string, kMaxActuators> actuatorPaths, blockPaths;
  ~Target() {
    if (address) lo_address_free(address);
  }
};

OscOutput::OscOutput(OscOutputConfig config, const Clock& clock)
    : QueuedOutput(clock, config.failsafe, config.heartbeat, 256), m_config(std::move(config)),
      m_target(std::make_unique<Target>()) {
  if (m_config.levelRate_hz < 1 || m_config.levelRate_hz > 4000)
    fail("OSC output: level rate ", m_config.levelRate_hz, " Hz outside 1..4000");
  addrinfo hints{};
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  if (const int e = getaddrinfo(m_config.host.c_str(), m_config.port.c_str(), &hints, &found); e != 0)
    fail("OSC output osc://", m_config.host, ":", m_config.port, ": cannot resolve host: ", gai_strerror(e));
  freeaddrinfo(found);
  m_target->address = lo_address_new(m_config.host.c_str(), m_config.port.c_str());
  if (!m_target->address) fail("OSC output osc://", m_config.host, ":", m_config.port, ": liblo refused the address");
  for (int a = 0; a < kMaxActuators; ++a) {
    const std::string_view name = actuatorName(ActuatorId(a));
    m_target->actuatorPaths[std::size_t(a)] = str("/vtouching/actuator/", name);
    m_target->blockPaths[std::size_t(a)] = str("/vtouching/block/", name);
  }
  startWriter("osc output");
}

OscOutput::~OscOutput() { stop(); }  // the writer's last act is zero levels

std::string OscOutput::name() const { return str("osc://", m_config.host, ":", m_config.port); }

// Levels go out every levels period: a frame waits up to one period for its message.
std::int64_t OscOutput::latency_ns() const { return 1'000'000'000 / std::max(1, m_config.levelRate_hz); }

std::string OscOutput::statusLine() const {
  const OscOutputStatus s = status();
  return str(s.target, " ", s.messagesSent, " messages, ", s.sendErrors, " errors", failsafeNote(s.failsafe),
             s.lastError.empty() ? std::string() : ", " + s.lastError);
}

OscOutputStatus OscOutput::status() const {
  OscOutputStatus s;
  s.target = str("osc://", m_config.host, ":", m_config.port);
  s.messagesSent = m_sent.load();
  s.sendErrors = m_errors.load();
  s.queueDropped = m_queue.dropped();
  s.failsafe = m_failsafe.lastReason();
  s.lastError = lastError();
  return s;
}

void OscOutput::count(int result) noexcept {
  if (result >= 0) {
    m_sent.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  m_errors.fetch_add(1, std::memory_order_relaxed);
  const char* why = lo_address_errstr(m_target->address);  // the address is the writer's own
  setLastError("send failed", why ? why : "unknown error");
}

void OscOutput::sendLevels(const ActuatorFrame& frame) noexcept {
  const int n = std::min<int>(frame.actuatorCount, kMaxActuators);
  lo_message levels = lo_message_new();
  lo_message frequencies = lo_message_new();
  for (int a = 0; a < n; ++a) {
    lo_message_add_float(levels, frame.intensity[std::size_t(a)]);
    lo_message_add_float(frequencies, frame.frequency_hz[std::size_t(a)]);
  }
  count(lo_send_message(m_target->address, "/vtouching/levels", levels));
  count(lo_send_message(m_target->address, "/vtouching/frequencies", frequencies));
  lo_message_free(levels);
  lo_message_free(frequencies);
  for (int a = 0; a < n; ++a) {
    count(lo_send(m_target->address, m_target->actuatorPaths[std::size_t(a)].c_str(), "ff",
                  frame.intensity[std::size_t(a)], frame.frequency_hz[std::size_t(a)]));
  }
}

void OscOutput::sendBlock(const ActuatorFrame& frame) noexcept {
  const int n = std::min<int>(frame.actuatorCount, kMaxActuators);
  const int length = std::min<int>(frame.blockLength, kMaxBlockSamples);
  for (int a = 0; a < n; ++a) {
    lo_message block = lo_message_new();
    lo_message_add_int32(block, std::int32_t(frame.sampleRate_hz));
    for (int i = 0; i < length; ++i) lo_message_add_float(block, frame.block[std::size_t(a)][std::size_t(i)]);
    count(lo_send_message(m_target->address, m_target->blockPaths[std::size_t(a)].c_str(), block));
    lo_message_free(block);
  }
}

void OscOutput::writerLoop() noexcept {
  const std::int64_t levelPeriod_ns = 1'000'000'000 / m_config.levelRate_hz;
  std::int64_t nextLevels_ns = m_clock.now_ns();
  std::uint64_t popped = 0;
  std::uint8_t actuators = 0;
  bool haveFrame = false, silent = true;
  ActuatorFrame frame, newest;
  while (true) {
    const bool ending = stopping();
    while (m_queue.pop(frame)) {
      ++popped;
      newest = frame;
      haveFrame = true;
      actuators = frame.actuatorCount;
      if (m_config.blocks && !ending && m_failsafe.evaluate(heartbeat(popped)) == FailsafeReason::None) sendBlock(frame);
    }
    const bool hold = ending || m_failsafe.evaluate(heartbeat(popped)) != FailsafeReason::None;
    const std::int64_t now = m_clock.now_ns();
    if (ending || now >= nextLevels_ns) {
      nextLevels_ns = std::max(nextLevels_ns + levelPeriod_ns, now);
      if (hold) {
        // Zero levels once per hold (and at the end); a listener keeps the last value it got.
        if (!silent || ending) sendLevels(ActuatorFrame::silent(actuators, now));
        silent = true;
      } else if (haveFrame) {
        sendLevels(newest);
        silent = false;
      }
    }
    if (ending) break;
    m_clock.sleepUntil(std::min(nextLevels_ns, now + kPoll_ns));
  }
}

}  // namespace vt::haptics
