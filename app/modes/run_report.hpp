#pragma once
// The end-of-run report every live mode prints (`run`, `client`; `--json` for machines):
// the consistency meter's figures, the haptic loop's timing and the real-time grants.
#include <nlohmann/json.hpp>

#include "modes/touch_pipeline.hpp"

namespace vt::app {

/// The consistency meter's figures (keys as in docs/app.md, "Consistency meter").
nlohmann::ordered_json consistencyJson(const ConsistencyReport& report);
/// What each real-time thread of this process was granted, and why not where refused.
nlohmann::ordered_json realtimeGrantsJson();
/// The pipeline's report: "consistency", "haptic_loop" (local loop only), "outputs", "realtime_grants".
nlohmann::ordered_json runReportJson(const TouchPipeline& pipeline);
/// Prints `report` as JSON (`json`) or as "key value" lines, and flushes.
void printReport(const nlohmann::ordered_json& report, bool json);

}  // namespace vt::app
