#include "vt/haptics/haptic_scene.hpp"

#include "vt/core/error.hpp"

namespace vt::haptics {

std::shared_ptr<const HapticScene> makeHapticScene(std::shared_ptr<const Scene> scene,
                                                    std::vector<VibrationMap> waveformMaps) {
  if (!scene) fail("haptics: no scene given");
  auto out = std::make_shared<HapticScene>();
  out->collision = std::make_shared<const collision::CollisionScene>(scene);
  auto maps = std::make_shared<std::vector<VibrationMap>>();
  maps->reserve(scene->vibrationMaps.size());
  for (std::size_t i = 0; i < scene->vibrationMaps.size(); ++i) {
    if (i < waveformMaps.size() && !waveformMaps[i].empty()) {
      maps->push_back(std::move(waveformMaps[i]));
    } else {
      maps->emplace_back(scene->vibrationMaps[i], str("scene vibration map #", i));
    }
  }
  out->maps = std::move(maps);
  return out;
}

}  // namespace vt::haptics
