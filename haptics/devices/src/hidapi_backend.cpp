// HidBackend over hidapi (hidraw backend on Linux).
#include <hidapi/hidapi.h>


#include "vt/core/error.hpp"
#include "vt/haptics/devices/hid_transport.hpp"

namespace vt::haptics::glove {
namespace {

std::string narrow(const wchar_t* text) {
  std::string out;
  if (!text) return out;
  for (; *text; ++text) out.push_back(*text < 0x80 ? char(*text) : '?');  // HID strings are ASCII in practice
  return out;
}

class HidapiDevice final : public HidDevice {
 public:
  explicit HidapiDevice(hid_device* device) : m_device(device) {}
  ~HidapiDevice() override { hid_close(m_device); }

  int write(std::span<const std::uint8_t> bytes) noexcept override {
    return hid_write(m_device, bytes.data(), bytes.size());
  }
  int read(std::span<std::uint8_t> out, int timeout_ms) noexcept override {
    return hid_read_timeout(m_device, out.data(), out.size(), timeout_ms);
  }
  int getFeature(std::span<std::uint8_t> out) noexcept override {
    return hid_get_feature_report(m_device, out.data(), out.size());
  }
  std::string lastError() const override {
    const std::string text = narrow(hid_error(m_device));
    return text.empty() ? "unknown hidapi error" : text;
  }

 private:
  hid_device* m_device;
};

class HidapiBackend final : public HidBackend {
 public:
  HidapiBackend() {
    // hid_init is process-wide; hid_exit is left to process exit so several backends coexist.
    static const int initResult = hid_init();
    if (initResult != 0) fail("hidapi: hid_init failed: ", narrow(hid_error(nullptr)));
  }

  std::vector<HidDeviceInfo> enumerate(std::uint16_t vendorId, std::uint16_t productId) override {
    std::vector<HidDeviceInfo> out;
    hid_device_info* list = hid_enumerate(vendorId, productId);  // nullptr when nothing matches
    for (const hid_device_info* d = list; d; d = d->next) {
      out.push_back({d->path ? d->path : "", d->vendor_id, d->product_id, narrow(d->serial_number),
                     narrow(d->manufacturer_string), narrow(d->product_string)});
    }
    hid_free_enumeration(list);
    return out;
  }

  std::unique_ptr<HidDevice> open(const std::string& path, std::string& error) override {
    hid_device* device = hid_open_path(path.c_str());
    if (!device) {
      error = str("hidapi: cannot open '", path, "': ", narrow(hid_error(nullptr)),
                  " (check /dev/hidraw* permissions, e.g. a udev rule)");
      return nullptr;
    }
    return std::make_unique<HidapiDevice>(device);
  }
};

}  // namespace

std::unique_ptr<HidBackend> makeHidapiBackend() { return std::make_unique<HidapiBackend>(); }

}  // namespace vt::haptics::glove
