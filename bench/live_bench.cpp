// `vt_bench live`: the visual-tactile consistency of the running program (tools/live): every
// live path with the default pose sampling and, as the baseline, with the newest pose only
// (keys `<path>_<figure>` and `<path>_<figure>_latest`). Figures: docs/PERFORMANCE.md
// ("Consistency in the running app"); `--check` holds the issue's goals (the ctest gates app.live.* hold them too, but
// for the desktop paths' p99 offsets: tools/live/src/live.cpp).
#include <cstdio>
#include <filesystem>

#include "bench.hpp"
#include "vt/live/live.hpp"

namespace vt::bench {

VT_BENCH_SUITE(live, "visual-tactile consistency of the running app: desktop, headset (xrsim), client/server") {
  nlohmann::ordered_json out;
  bool missed = false;
  for (const std::string& path : live::pathNames()) {
    for (const char* sampling : {"predict", "latest"}) {
      if (options.quick && std::string(sampling) == "latest") continue;
      live::LiveOptions run;
      run.work = std::filesystem::temp_directory_path() / "vt_bench_live" / (path + "_" + sampling);
      run.sampling = sampling;
      const nlohmann::ordered_json figures = live::runPath(path, run);
      const std::string suffix = std::string(sampling) == "latest" ? "_latest" : "";
      for (const auto& [key, value] : figures.items()) out[path + "_" + key + suffix] = value;
      if (suffix.empty()) {
        for (const std::string& miss : live::missedGoals(path, figures, live::GoalSet::kIssue)) {
          std::fprintf(stderr, "live: %s\n", miss.c_str());
          missed = true;
        }
      }
      if (!options.json) std::printf("%-10s %-8s %s\n", path.c_str(), sampling, figures.dump().c_str());
    }
  }
  if (options.json) std::printf("%s\n", out.dump(2).c_str());
  return options.check && missed ? 1 : 0;
}

}  // namespace vt::bench
