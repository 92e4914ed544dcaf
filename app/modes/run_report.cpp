#include "modes/run_report.hpp"

#include <cstdio>

#include "vt/core/realtime.hpp"

namespace vt::app {
namespace {

nlohmann::ordered_json offsetJson(const OffsetStats& s) {
  return {{"p50", s.p50}, {"p99", s.p99}, {"max", s.max}, {"signed_p99", s.signedP99}, {"count", s.count}};
}

}  // namespace

nlohmann::ordered_json consistencyJson(const ConsistencyReport& r) {
  nlohmann::ordered_json fingers = nlohmann::ordered_json::object();
  for (const FingerConsistency& f : r.fingers)
    fingers[f.name] = {{"offset_mm", offsetJson(f.offset_mm)},
                       {"offset_ms", offsetJson(f.offset_ms)},
                       {"moving_contact_ticks", f.movingContactTicks},
                       {"frozen_ticks", f.frozenTicks},
                       {"frozen_run_ms_max", f.frozenRunMax_ms}};
  return {{"frames_compared", r.framesCompared},
          {"display_rate_hz", r.displayRate_hz},
          {"felt_latency_ms", double(r.feltLatency_ns) * 1e-6},
          {"offset_mm", offsetJson(r.offset_mm)},
          {"offset_ms", offsetJson(r.offset_ms)},
          {"moving_contact_ticks", r.movingContactTicks},
          {"frozen_moving_pct", r.frozenMovingPct},
          {"frozen_run_ms_max", r.frozenRunMax_ms},
          {"stops", r.stops},
          {"stop_overshoot_ms", r.stopOvershoot_ms},
          {"stop_overshoot_mm", r.stopOvershoot_mm},
          {"fingers", fingers}};
}

nlohmann::ordered_json realtimeGrantsJson() {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const ThreadGrant& g : realtimeGrants()) {
    out.push_back({{"thread", g.thread},
                   {"method", realtimeMethodName(g.grant.method)},
                   {"policy", schedulingPolicyName(g.grant.policy)},
                   {"priority", g.grant.priority},
                   {"timer_slack_ns", g.grant.timerSlack_ns},
                   {"refusal", g.refusal}});
  }
  return out;
}

nlohmann::ordered_json runReportJson(const TouchPipeline& pipeline) {
  nlohmann::ordered_json out;
  out["consistency"] = consistencyJson(pipeline.consistency());
  if (const haptics::HapticLoop* loop = pipeline.loop()) {
    const haptics::LoopStats s = loop->stats();
    out["haptic_loop"] = {{"ticks", s.ticks},           {"overruns", s.overruns},         {"stale_poses", s.stalePoses},
                          {"predicted_ticks", s.predictedTicks}, {"tick_p99_us", s.tickP99_us}, {"jitter_p99_us", s.jitterP99_us},
                          {"pacing", haptics::loopPacingName(loop->config().pacing)},
                          {"run_tick_p50_us", s.runTickP50_us}, {"run_tick_p99_us", s.runTickP99_us},
                          {"run_tick_max_us", s.runTickMax_us},
                          {"display_lag_ms", double(loop->displayLag_ns()) * 1e-6},
                          {"output_latency_ms", double(loop->outputLatency_ns()) * 1e-6}};
  }
  nlohmann::ordered_json outputs = nlohmann::ordered_json::array();
  for (const auto& sink : pipeline.sinks())
    outputs.push_back({{"name", sink->name()}, {"felt", sink->felt()}, {"latency_ms", double(sink->latency_ns()) * 1e-6}});
  out["outputs"] = outputs;
  out["realtime_grants"] = realtimeGrantsJson();
  return out;
}

void printReport(const nlohmann::ordered_json& report, bool json) {
  if (json) std::printf("%s\n", report.dump(2).c_str());
  else
    for (const auto& [key, value] : report.items()) std::printf("%-22s %s\n", key.c_str(), value.dump().c_str());
  std::fflush(stdout);
}

}  // namespace vt::app
