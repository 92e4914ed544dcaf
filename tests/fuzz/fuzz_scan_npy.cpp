// Scan logs as .npy arrays from outside (the authors' published form).
#include <cstdint>
#include <string_view>

#include "vt/acquisition/scan.hpp"
#include "vt/core/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const auto passes = vt::acq::parseLogNpy(bytes, "fuzz input", vt::acq::kAccelColumns);
    for (const auto& pass : passes) {
      if (pass.t_s.empty() || pass.t_s.size() != pass.v.size()) __builtin_trap();
      for (std::size_t i = 1; i < pass.t_s.size(); ++i) {
        if (!(pass.t_s[i] > pass.t_s[i - 1])) __builtin_trap();  // accepted logs are strictly monotonic
      }
    }
    // What formatLogNpy writes, parseLogNpy reads back unchanged.
    const auto again = vt::acq::parseLogNpy(vt::acq::formatLogNpy(passes), "fuzz output", vt::acq::kAccelColumns);
    if (again.size() != passes.size()) __builtin_trap();
    for (std::size_t p = 0; p < passes.size(); ++p) {
      if (again[p].t_s != passes[p].t_s || again[p].v != passes[p].v) __builtin_trap();
    }
  } catch (const vt::Error&) {
  }
  return 0;
}
