// Scan logs and calibration points from outside (robot, accelerometer, hand-marked pixels).
#include <cstdint>
#include <string_view>

#include "vt/acquisition/scan.hpp"
#include "vt/core/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto passes = vt::acq::parseLogCsv(text, "fuzz input", vt::acq::kAccelColumns);
    for (const auto& pass : passes) {
      if (pass.t_s.empty() || pass.t_s.size() != pass.v.size()) __builtin_trap();
      for (std::size_t i = 1; i < pass.t_s.size(); ++i) {
        if (!(pass.t_s[i] > pass.t_s[i - 1])) __builtin_trap();  // accepted logs are strictly monotonic
      }
    }
  } catch (const vt::Error&) {
  }
  try {
    vt::acq::parseCalibrationCsv(text, "fuzz input");
  } catch (const vt::Error&) {
  }
  try {
    vt::acq::parseScanConfig(text, "fuzz input");
  } catch (const vt::Error&) {
  }
  return 0;
}
