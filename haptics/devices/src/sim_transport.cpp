#include "vt/haptics/devices/sim_transport.hpp"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <thread>

namespace vt::haptics::glove {

struct SimTransportState {
  SimTransportState(SimulatedGlove& g, std::uint16_t vid, std::uint16_t pid, std::chrono::nanoseconds period)
      : glove(g), vendorId(vid), productId(pid), inputPeriod(period) {}
  SimulatedGlove& glove;
  std::uint16_t vendorId;
  std::uint16_t productId;
  std::chrono::nanoseconds inputPeriod;
  std::atomic<bool> present{true};
  std::atomic<std::uint64_t> plugGeneration{0};  // bumped on unplug: old handles die
  std::atomic<int> failingOpens{0};
  std::atomic<bool> failingWrites{false};
  std::atomic<std::uint64_t> opens{0};
};

namespace {

class SimDevice final : public HidDevice {
 public:
  SimDevice(std::shared_ptr<SimTransportState> state, std::uint64_t generation)
      : m_state(std::move(state)), m_generation(generation), m_nextInput(std::chrono::steady_clock::now()) {}

  int write(std::span<const std::uint8_t> bytes) noexcept override {
    if (!alive()) return -1;
    if (m_state->failingWrites.load()) return error("simulated write I/O error");
    m_state->glove.receiveOutput(bytes);  // a real device also swallows bad reports silently
    return int(bytes.size());
  }

  int read(std::span<std::uint8_t> out, int timeout_ms) noexcept override {
    if (!alive()) return -1;
    // Input reports come at the device's own rate, in real time (like a USB interrupt endpoint).
    const auto now = std::chrono::steady_clock::now();
    if (m_nextInput > now) {
      const auto wait = std::min<std::chrono::nanoseconds>(m_nextInput - now, std::chrono::milliseconds(timeout_ms));
      std::this_thread::sleep_for(wait);
      if (!alive()) return -1;
      if (std::chrono::steady_clock::now() < m_nextInput) return 0;
    }
    m_nextInput = std::max(m_nextInput + m_state->inputPeriod, std::chrono::steady_clock::now() - m_state->inputPeriod);
    Report report;
    m_state->glove.makeInputReport(report);
    const std::size_t n = std::min(out.size(), report.size());
    std::copy_n(report.begin(), n, out.begin());
    return int(n);
  }

  int getFeature(std::span<std::uint8_t> out) noexcept override {
    if (!alive()) return -1;
    const int n = m_state->glove.readFeature(out);
    return n < 0 ? error("unknown feature report id") : n;
  }

  std::string lastError() const override {
    const std::lock_guard lock(m_errorMutex);
    return m_error;
  }

 private:
  bool alive() noexcept {
    if (m_state->plugGeneration.load() == m_generation && m_state->present.load()) return true;
    error("device disconnected");
    return false;
  }
  int error(const char* text) noexcept {
    const std::lock_guard lock(m_errorMutex);
    m_error = text;  // short literal: fits the small-string buffer, no allocation failure path
    return -1;
  }

  std::shared_ptr<SimTransportState> m_state;
  std::uint64_t m_generation;
  std::chrono::steady_clock::time_point m_nextInput;  // reader thread only
  mutable std::mutex m_errorMutex;
  std::string m_error;
};

}  // namespace

SimGloveBackend::SimGloveBackend(SimulatedGlove& glove, std::uint16_t vendorId, std::uint16_t productId,
                                 int inputRate_hz)
    : m_state(std::make_shared<SimTransportState>(
          glove, vendorId, productId, std::chrono::nanoseconds(1'000'000'000 / std::max(inputRate_hz, 1)))) {}

SimGloveBackend::~SimGloveBackend() = default;

std::vector<HidDeviceInfo> SimGloveBackend::enumerate(std::uint16_t vendorId, std::uint16_t productId) {
  if (!m_state->present.load()) return {};
  if ((vendorId && vendorId != m_state->vendorId) || (productId && productId != m_state->productId)) return {};
  return {{kPath, m_state->vendorId, m_state->productId, m_state->glove.info().serial.data(), "V-Touching",
           "Simulated Avatar-style glove"}};
}

std::unique_ptr<HidDevice> SimGloveBackend::open(const std::string& path, std::string& error) {
  if (path != kPath || !m_state->present.load()) {
    error = "sim: no device at '" + path + "'";
    return nullptr;
  }
  if (m_state->failingOpens.load() > 0) {
    m_state->failingOpens.fetch_sub(1);
    error = "sim: simulated open failure";
    return nullptr;
  }
  m_state->opens.fetch_add(1);
  return std::make_unique<SimDevice>(m_state, m_state->plugGeneration.load());
}

void SimGloveBackend::setPresent(bool present) noexcept {
  if (!present) m_state->plugGeneration.fetch_add(1);
  m_state->present.store(present);
}

void SimGloveBackend::failNextOpens(int count) noexcept { m_state->failingOpens.store(count); }
void SimGloveBackend::failWrites(bool fail) noexcept { m_state->failingWrites.store(fail); }
std::uint64_t SimGloveBackend::opens() const noexcept { return m_state->opens.load(); }

}  // namespace vt::haptics::glove
