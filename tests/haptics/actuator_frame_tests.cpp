#include <catch2/catch.hpp>

#include <type_traits>

#include "vt/haptics/actuator_frame.hpp"

TEST_CASE("Actuator frames are trivially copyable and the silent frame is all zeros") {
  STATIC_REQUIRE(std::is_trivially_copyable_v<vt::haptics::ActuatorFrame>);
  const auto frame = vt::haptics::ActuatorFrame::silent(10, 42);
  CHECK(frame.actuatorCount == 10);
  CHECK(frame.t_ns == 42);
  for (float level : frame.intensity) CHECK(level == 0.0f);
}

TEST_CASE("Actuators are named as OpenXR names the fingers, and the older \"pinky\" names still read") {
  using vt::haptics::ActuatorId;
  CHECK(vt::haptics::actuatorName(ActuatorId::Little) == "little");
  CHECK(vt::haptics::actuatorName(ActuatorId::PalmLittleDown) == "palm-little-down");
  for (int a = 0; a < vt::haptics::kMaxActuators; ++a) {
    const auto id = ActuatorId(a);
    CHECK(vt::haptics::actuatorName(id).find("pinky") == std::string_view::npos);
    CHECK(vt::haptics::actuatorFromName(vt::haptics::actuatorName(id)) == id);
    CHECK(vt::haptics::actuatorFromName(vt::haptics::legacyActuatorName(id)) == id);
  }
  CHECK(vt::haptics::actuatorFromName("pinky") == ActuatorId::Little);
  CHECK(vt::haptics::actuatorFromName("palm-pinky-up") == ActuatorId::PalmLittleUp);
  CHECK_FALSE(vt::haptics::actuatorFromName("pinkie").has_value());
}
