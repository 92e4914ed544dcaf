#include <catch2/catch.hpp>

#include <type_traits>

#include "vt/haptics/actuator_frame.hpp"

TEST_CASE("Actuator frames are trivially copyable and the silent frame is all zeros") {
  STATIC_REQUIRE(std::is_trivially_copyable_v<vt::haptics::ActuatorFrame>);
  const auto frame = vt::haptics::ActuatorFrame::silent(10, 42);
  CHECK(frame.actuatorCount == 10);
  CHECK(frame.t_ns == 42);
  for (float level : frame.intensity) CHECK(level == 0.0f);
  CHECK(vt::haptics::actuatorName(vt::haptics::ActuatorId::PalmPinkyDown) == "palm-pinky-down");
}
