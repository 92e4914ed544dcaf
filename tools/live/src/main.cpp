// vt_live: runs live consistency paths (vt/live/live.hpp) and prints their figures; with
// --check it holds the ctest gates' goals (GoalSet::kCtest), runs a path that missed one once
// more and fails (exit 1) when that run misses too, and exits 77 (skipped) when the machine cannot run a path. The ctest gates of issue 25
// (tests/app/CMakeLists.txt) call it.
//   vt_live [--path NAME]... [--sampling predict|latest] [--check] [--work DIR]
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "vt/live/live.hpp"

int main(int argc, char** argv) {
  std::vector<std::string> paths;
  vt::live::LiveOptions options;
  options.work = std::filesystem::temp_directory_path() / "vt_live";
  bool check = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--path" && i + 1 < argc) paths.push_back(argv[++i]);
    else if (arg == "--sampling" && i + 1 < argc) options.sampling = argv[++i];
    else if (arg == "--work" && i + 1 < argc) options.work = argv[++i];
    else if (arg == "--check") check = true;
    else {
      std::fprintf(stderr, "vt_live: unknown argument '%s'\nusage: vt_live [--path NAME]... [--sampling predict|latest] "
                           "[--check] [--work DIR]\n", arg.c_str());
      return 2;
    }
  }
  if (paths.empty()) paths = vt::live::pathNames();
  nlohmann::ordered_json out;
  std::vector<std::string> misses;
  bool ran = false;
  try {
    for (const std::string& path : paths) {
      vt::live::LiveOptions one = options;
      one.work = options.work / path;
      nlohmann::ordered_json figures = vt::live::runPath(path, one);
      std::vector<std::string> missed = vt::live::missedGoals(path, figures, vt::live::GoalSet::kCtest);
      if (check && !missed.empty()) {
        // One more run: on a shared 2-core host a stall of the machine can spoil one run (net5
        // once in six local CI runs: |offset| p99 11.2 ms, 5.5 ms in four runs after). A path
        // fails when both runs miss; the first run's misses are printed either way.
        for (const std::string& miss : missed) std::fprintf(stderr, "vt_live: first run: %s\n", miss.c_str());
        std::fprintf(stderr, "vt_live: %s: running it once more\n", path.c_str());
        out[path + ", first run"] = figures;
        figures = vt::live::runPath(path, one);
        missed = vt::live::missedGoals(path, figures, vt::live::GoalSet::kCtest);
      }
      ran = ran || !figures.contains("skipped");
      out[path] = figures;
      misses.insert(misses.end(), missed.begin(), missed.end());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vt_live: %s\n", e.what());
    return 1;
  }
  std::printf("%s\n", out.dump(2).c_str());
  if (!ran) {
    std::printf("vt_live: skipped: %s\n", out.begin()->value("skipped", "").c_str());
    return 77;
  }
  for (const std::string& miss : misses) std::fprintf(stderr, "vt_live: %s\n", miss.c_str());
  if (check && misses.empty()) std::printf("vt_live: every gate met\n");
  return check && !misses.empty() ? 1 : 0;
}
