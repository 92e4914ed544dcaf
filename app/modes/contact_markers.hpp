#pragma once
// The rings the renderer draws where the hand touches (FrameDesc::contacts), from what the
// touch state knows of each contact point. Main thread only (read-only collision queries).
#include <span>
#include <vector>

#include "modes/touch_pipeline.hpp"
#include "vt/collision/collision_scene.hpp"
#include "vt/haptics/haptic_loop.hpp"
#include "vt/renderer/frame.hpp"

namespace vt::app {

/// One marker per contact point whose newest trace touches (`latest[c]` for contact c of
/// `config`), with the trace's intensity (clamped to 0..1), on the surface nearest the drawn
/// hand's joint of that contact (the visual proxy rests there); none where no surface is near it.
void appendContactMarkers(std::span<const haptics::ContactTrace> latest, const haptics::HapticConfig& config,
                          const HandPose& drawn, const collision::CollisionScene& world,
                          std::vector<renderer::ContactMarker>& out);
/// The same from a pipeline's newest traces (client mode: the played levels, no position of their own).
void appendContactMarkers(const TouchPipeline& pipeline, const HandPose& drawn, const collision::CollisionScene& world,
                          std::vector<renderer::ContactMarker>& out);

}  // namespace vt::app
