#pragma once
// The paper's claim measured on the running program (issue 25): each live path runs the real
// `vtouching` binary as a user would, over a stripe grating of known period with the motions a
// person makes (minimum-jerk reaches, stops, reversals, a slow slide, lift-off and re-touch,
// 0.02-0.5 m/s), and reads the app's own end-of-session report (its consistency meter) and
// recordings against the scripted ground truth:
//   desktop     the preview under Xvfb, a scripted mouse (--cursor-script), natural frame rate
//   desktop10   the same at a forced 10 frames per second (--max-fps 10)
//   xr72, xr90  headset mode on xrsim in real time at 72 / 90 Hz, scripted hand tracking
//   net0, net5  `serve` and a desktop `client` on loopback, 0 % and 5 % loss both ways,
//               measured at the client's actuator output (codec, jitter buffer, playout)
// Used by `vt_bench live` and by the ctest gates (tools/live/main.cpp, `vt_live --check`).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vt::live {

/// The paths, in report order.
const std::vector<std::string>& pathNames();

struct LiveOptions {
  std::filesystem::path work;   // scratch folder (scripts, recordings, logs)
  std::string sampling = "predict";  // --pose-sampling of the app (the baseline: "latest")
  bool keep = false;            // keep the scratch files (else removed after a passing run)
  // Rounds of the person's motions (7.5 s each): three give 100 - 600 displayed frames, so a
  // run's p99 is a percentile, not its slowest frame. The sanitizer stages run one (no goal held).
  int rounds = 3;
};

/// Runs one path; the figures keyed as in docs/PERFORMANCE.md ("frozen_moving_pct",
/// "frozen_run_ms_max", "offset_ms_p99", "offset_mm_p99", "stop_overshoot_ms",
/// "stop_overshoot_mm", "freq_error_pct", and context: "frame_rate_hz", "frames_compared", ...),
/// or {"skipped": reason} when the machine cannot run it (no xvfb-run). Throws vt::Error naming
/// the process and its log when a run fails.
nlohmann::ordered_json runPath(const std::string& path, const LiveOptions& options);

/// Which goals missedGoals holds: the issue's own (the benchmark, `vt_bench live --check`), or
/// the ctest gates', where the desktop paths' p99 offsets are printed and their medians held
/// instead (live.cpp says why).
enum class GoalSet { kIssue, kCtest };

/// The goals of `set` for a path's figures: one line per miss, empty when all hold.
std::vector<std::string> missedGoals(const std::string& path, const nlohmann::ordered_json& figures, GoalSet set);

/// A path's runs under a gate, first to last: each run's figures and the goals it missed.
struct GatedRuns {
  std::vector<nlohmann::ordered_json> figures;
  std::vector<std::vector<std::string>> missed;

  /// The gate holds: the last run missed nothing (every earlier one missed something).
  bool met() const { return !missed.empty() && missed.back().empty(); }
};

/// Runs `run` and, while its last run misses one of `goals`, up to `reruns` times more, calling
/// `rerunning(run number, its misses)` before each rerun: a path fails its gate only when every
/// run misses (`vt_live --check`; main.cpp says why). A skipped run misses nothing.
GatedRuns runGated(const std::function<nlohmann::ordered_json()>& run,
                   const std::function<std::vector<std::string>(const nlohmann::ordered_json&)>& goals, int reruns,
                   const std::function<void(int, const std::vector<std::string>&)>& rerunning = {});

}  // namespace vt::live
