#include "vt/haptics/actuator_frame.hpp"

namespace vt::haptics {

std::string_view actuatorName(ActuatorId id) noexcept {
  static constexpr std::string_view kNames[kMaxActuators] = {
      "thumb", "index", "middle", "ring", "pinky",
      "palm-index-up", "palm-index-down", "palm-middle-up", "palm-pinky-up", "palm-pinky-down"};
  const auto i = std::size_t(id);
  return i < std::size(kNames) ? kNames[i] : std::string_view("unknown");
}

}  // namespace vt::haptics
