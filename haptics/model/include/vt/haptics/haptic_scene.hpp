#pragma once
// The immutable world the haptic thread touches: collision BVHs plus vibration maps. An
// edit builds a new HapticScene and publishes it (HapticLoop::publishScene); nothing in a
// published snapshot ever changes.
#include <memory>
#include <vector>

#include "vt/collision/collision_scene.hpp"
#include "vt/haptics/vibration_map.hpp"
#include "vt/scene/scene.hpp"

namespace vt::haptics {

/// One immutable world snapshot; shared read-only by the haptic thread.
struct HapticScene {
  std::shared_ptr<const collision::CollisionScene> collision;
  /// Indexed like Scene::vibrationMaps (Material::vibrationMap); shared between snapshots.
  std::shared_ptr<const std::vector<VibrationMap>> maps;

  const Scene& scene() const noexcept { return collision->scene(); }
};

/// Builds BVHs and wraps the scene's vibration maps. `waveformMaps` (optional, same indices)
/// replaces maps that have per-taxel waveforms. Setup threads; throws vt::Error.
std::shared_ptr<const HapticScene> makeHapticScene(std::shared_ptr<const Scene> scene,
                                                    std::vector<VibrationMap> waveformMaps = {});

}  // namespace vt::haptics
