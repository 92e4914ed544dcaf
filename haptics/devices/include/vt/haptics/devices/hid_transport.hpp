#pragma once
// HID transport, kept apart from report encoding: a backend enumerates and opens devices,
// a device moves whole reports. Implementations: hidapi (real gloves) and the simulated glove.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace vt::haptics::glove {

/// One enumerated HID device.
struct HidDeviceInfo {
  std::string path;  // backend-specific, passed back to open()
  std::uint16_t vendorId = 0;
  std::uint16_t productId = 0;
  std::string serial;
  std::string manufacturer;
  std::string product;
};

/// An open HID device. write() and getFeature() are called by one thread, read() by another
/// (the driver's writer and reader threads); implementations must allow that pairing.
/// Results: bytes transferred, 0 on read timeout, -1 on error (then lastError() says why).
class HidDevice {
 public:
  virtual ~HidDevice() = default;
  /// Sends one output report; bytes[0] is the report ID.
  virtual int write(std::span<const std::uint8_t> bytes) noexcept = 0;
  /// Waits up to timeout_ms for one input report (report ID first).
  virtual int read(std::span<std::uint8_t> out, int timeout_ms) noexcept = 0;
  /// Reads a feature report; out[0] must hold the report ID on entry.
  virtual int getFeature(std::span<std::uint8_t> out) noexcept = 0;
  /// Text of the last failure on this device (writer or reader thread).
  virtual std::string lastError() const = 0;
};

/// Finds and opens HID devices. Setup/device threads only.
class HidBackend {
 public:
  virtual ~HidBackend() = default;
  /// Devices matching vendorId/productId (0 = any); empty when none are attached.
  virtual std::vector<HidDeviceInfo> enumerate(std::uint16_t vendorId, std::uint16_t productId) = 0;
  /// Opens the device at `path`; nullptr with `error` filled on failure.
  virtual std::unique_ptr<HidDevice> open(const std::string& path, std::string& error) = 0;
};

/// The real thing, over hidapi (hidraw on Linux). Throws vt::Error when hidapi cannot start.
std::unique_ptr<HidBackend> makeHidapiBackend();

}  // namespace vt::haptics::glove
