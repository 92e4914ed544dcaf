#pragma once
// Headset mode (`vtouching --xr`): the OpenXR session renders the scene to both eyes, the
// runtime's hand tracking (or controllers) drives the hand and the haptic loop, and the
// actuator output also vibrates the controllers. Main thread only.
#include <optional>

#include "modes/desktop_mode.hpp"

namespace vt::app {

/// Runs until the runtime ends the session (or --frames). nullopt when no headset is usable:
/// the reason has been printed, and the caller falls back to the desktop (or fails when forced).
std::optional<int> runHeadset(const DesktopOptions& options);

}  // namespace vt::app
