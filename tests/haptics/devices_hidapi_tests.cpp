#include <catch2/catch.hpp>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "test_support.hpp"
#include "vt/haptics/devices/glove_driver.hpp"
#include "vt/haptics/devices/hid_transport.hpp"

using namespace vt::haptics::glove;

TEST_CASE("hidapi enumeration with no glove attached returns an empty list") {
  auto backend = makeHidapiBackend();
  // No glove is attached to build machines (set VT_GLOVE_ATTACHED=1 on one that has a glove).
  const auto gloves = backend->enumerate(kDefaultVendorId, kDefaultProductId);
  if (std::getenv("VT_GLOVE_ATTACHED")) VT_SKIP("a real glove is attached");
  CHECK(gloves.empty());
  CHECK(backend->enumerate(kDefaultVendorId, 0xFFF0).empty());
  std::string error;
  CHECK(backend->open("/dev/nonexistent-hidraw", error) == nullptr);
  CHECK_FALSE(error.empty());
}

TEST_CASE("Glove driver over hidapi without a device stays disconnected and stops cleanly") {
  auto backend = makeHidapiBackend();
  GloveDriverConfig config;
  config.productId = 0xFFF0;  // a PID nobody uses, so a developer's glove does not interfere
  GloveDriver driver(*backend, config);
  driver.submit(vt::haptics::ActuatorFrame::silent(10, 0));
  GloveStatus status;
  for (int i = 0; i < 2000 && (status = driver.status()).lastError.empty(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  CHECK_FALSE(status.connected);
  CHECK(status.lastError.find("no glove 1209:fff0") != std::string::npos);
  driver.stop();
  CHECK(driver.status().reportsSent == 0);
}
