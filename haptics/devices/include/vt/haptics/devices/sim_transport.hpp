#pragma once
// A HidBackend whose one device is a SimulatedGlove, with fault injection (unplug, failing
// opens and writes) so the driver's reconnect and failsafe paths run against real report bytes.
#include <atomic>
#include <cstdint>
#include <memory>

#include "vt/haptics/devices/hid_transport.hpp"
#include "vt/haptics/devices/sim_glove.hpp"

namespace vt::haptics::glove {

struct SimTransportState;

class SimGloveBackend final : public HidBackend {
 public:
  /// `glove` must outlive the backend and every device it opens.
  explicit SimGloveBackend(SimulatedGlove& glove, std::uint16_t vendorId = kDefaultVendorId,
                           std::uint16_t productId = kDefaultProductId, int inputRate_hz = 100);
  ~SimGloveBackend() override;

  std::vector<HidDeviceInfo> enumerate(std::uint16_t vendorId, std::uint16_t productId) override;
  std::unique_ptr<HidDevice> open(const std::string& path, std::string& error) override;

  /// Any thread: unplug (false) or plug in (true). Unplugging kills every open handle for good.
  void setPresent(bool present) noexcept;
  /// Any thread: the next `count` open() calls fail.
  void failNextOpens(int count) noexcept;
  /// Any thread: while set, writes fail as an I/O error (the handle stays "open").
  void failWrites(bool fail) noexcept;
  /// Successful open() calls so far.
  std::uint64_t opens() const noexcept;

  /// The HID path under which the simulated glove enumerates.
  static constexpr const char* kPath = "sim:glove0";

 private:
  std::shared_ptr<SimTransportState> m_state;
};

}  // namespace vt::haptics::glove
