#include "vt/haptics/actuator_frame.hpp"

namespace vt::haptics {

namespace {

constexpr std::string_view kNames[kMaxActuators] = {
    "thumb", "index", "middle", "ring", "little",
    "palm-index-up", "palm-index-down", "palm-middle-up", "palm-little-up", "palm-little-down"};
constexpr std::string_view kLegacyNames[kMaxActuators] = {
    "thumb", "index", "middle", "ring", "pinky",
    "palm-index-up", "palm-index-down", "palm-middle-up", "palm-pinky-up", "palm-pinky-down"};

}  // namespace

std::string_view actuatorName(ActuatorId id) noexcept {
  const auto i = std::size_t(id);
  return i < std::size(kNames) ? kNames[i] : std::string_view("unknown");
}

std::string_view legacyActuatorName(ActuatorId id) noexcept {
  const auto i = std::size_t(id);
  return i < std::size(kLegacyNames) ? kLegacyNames[i] : std::string_view("unknown");
}

std::optional<ActuatorId> actuatorFromName(std::string_view name) noexcept {
  for (std::size_t i = 0; i < std::size(kNames); ++i)
    if (name == kNames[i] || name == kLegacyNames[i]) return ActuatorId(i);
  return std::nullopt;
}

}  // namespace vt::haptics
