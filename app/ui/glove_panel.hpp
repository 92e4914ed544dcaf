#pragma once
// ImGui panel for the glove: the actuators' levels on a hand diagram and the driver's status.
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/devices/glove_driver.hpp"
#include "vt/haptics/devices/sim_glove.hpp"

namespace vt::app {

/// UI thread, between ImGui::NewFrame() and ImGui::Render(): draws a "Glove" window showing
/// every actuator of `frame` on a right hand (palm view) and the `status` lines below it; with
/// a simulated glove, also its keep-alive state and finger-flexion sliders that drive it.
void drawGlovePanel(const haptics::ActuatorFrame& frame, const haptics::glove::GloveStatus& status,
                    haptics::glove::SimulatedGlove* simulated = nullptr);

}  // namespace vt::app
