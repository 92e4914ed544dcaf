#pragma once
// Tactile gains across a dataset's objects: absolute intensity from NAME_map.json and the
// optional gain table. Private to vt::scene; setup thread only.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "vt/scene/loaders.hpp"

namespace vt {

/// The [min_g, max_g] of a map's 16-bit PNG from NAME_map.json (`normalisation` of the main map, or
/// of `across` when `across`), or nullopt when the metadata does not record both as numbers.
std::optional<std::array<double, 2>> pngRange_g(const nlohmann::json& meta, bool across);

/// The peak (g) both maps of a two-direction object are scaled by when each records its own range
/// (V / peak: one physical scale with 0 g at 0, so the across map is felt); 0 otherwise.
double twoDirectionPeak_g(const nlohmann::json& meta);

/// Scales materials[i].tactileGain of the objects `names` (material i = object i) as `options`
/// asks; `metas[i]` is NAME_map.json (null when absent). Sets scene.intensity to what was done.
void applyDatasetIntensity(Scene& scene, const std::vector<std::string>& names,
                           const std::vector<nlohmann::json>& metas, const DatasetSceneOptions& options);

}  // namespace vt
