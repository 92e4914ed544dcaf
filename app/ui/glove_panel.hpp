#pragma once
// ImGui panel for the glove: the actuators' levels on a hand diagram and the driver's status.
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/devices/glove_driver.hpp"

namespace vt::app {

/// UI thread, between ImGui::NewFrame() and ImGui::Render(): draws a "Glove" window showing
/// every actuator of `frame` on a right hand (palm view) and the `status` lines below it.
void drawGlovePanel(const haptics::ActuatorFrame& frame, const haptics::glove::GloveStatus& status);

}  // namespace vt::app
