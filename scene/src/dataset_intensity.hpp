#pragma once
// Tactile gains across a dataset's objects: absolute intensity from NAME_map.json and the
// optional gain table. Private to vt::scene; setup thread only.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "vt/scene/loaders.hpp"

namespace vt {

/// Scales materials[i].tactileGain of the objects `names` (material i = object i) as `options`
/// asks; `metas[i]` is NAME_map.json (null when absent). Sets scene.intensity to what was done.
void applyDatasetIntensity(Scene& scene, const std::vector<std::string>& names,
                           const std::vector<nlohmann::json>& metas, const DatasetSceneOptions& options);

}  // namespace vt
