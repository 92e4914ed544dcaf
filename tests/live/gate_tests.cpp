#include <catch2/catch.hpp>

#include "vt/live/live.hpp"

using vt::live::GatedRuns;
using vt::live::runGated;
using Json = nlohmann::ordered_json;

namespace {

// A fake path: run k (from 0) reports {"miss": misses[k]}, and a run misses its goal when that
// is true, so a test scripts which runs miss without starting the app.
struct ScriptedPath {
  std::vector<bool> misses;
  int runs = 0;
  std::vector<int> announced;  // the run numbers rerunning() was told of

  GatedRuns gate(int reruns) {
    return runGated([&] { return Json{{"run", runs}, {"miss", bool(misses[std::size_t(runs++)])}}; },
                    [](const Json& f) {
                      return f["miss"].get<bool>() ? std::vector<std::string>{"run " + f["run"].dump() + " missed"}
                                                   : std::vector<std::string>{};
                    },
                    reruns, [&](int run, const std::vector<std::string>& missed) {
                      CHECK(missed.size() == 1);
                      announced.push_back(run);
                    });
  }
};

}  // namespace

TEST_CASE("A live gate reruns a missing path and fails only when every run misses") {
  SECTION("met at once: one run") {
    ScriptedPath path{{false}};
    const GatedRuns runs = path.gate(2);
    CHECK(runs.met());
    CHECK(runs.figures.size() == 1);
    CHECK(path.announced.empty());
  }
  SECTION("two misses, then met: three runs, every figure kept in order") {
    ScriptedPath path{{true, true, false}};
    const GatedRuns runs = path.gate(2);
    CHECK(runs.met());
    REQUIRE(runs.figures.size() == 3);
    for (int k = 0; k < 3; ++k) CHECK(runs.figures[std::size_t(k)]["run"] == k);
    CHECK(runs.missed[0] == std::vector<std::string>{"run 0 missed"});
    CHECK(path.announced == std::vector<int>{1, 2});
  }
  SECTION("every run misses: three runs, failed") {
    ScriptedPath path{{true, true, true, false}};
    const GatedRuns runs = path.gate(2);
    CHECK_FALSE(runs.met());
    CHECK(runs.figures.size() == 3);
    CHECK(path.runs == 3);  // no fourth run, though it would have met
  }
  SECTION("no reruns (vt_live without --check): one run, its misses kept") {
    ScriptedPath path{{true, false}};
    const GatedRuns runs = path.gate(0);
    CHECK_FALSE(runs.met());
    CHECK(runs.figures.size() == 1);
    CHECK(runs.missed.back().size() == 1);
    CHECK(path.announced.empty());
  }
}

TEST_CASE("A skipped live path misses no goal, so its gate never reruns it") {
  int runs = 0;
  const GatedRuns gated = runGated(
      [&] {
        ++runs;
        return Json{{"skipped", "no xvfb-run"}};
      },
      [](const Json& f) { return vt::live::missedGoals("desktop", f, vt::live::GoalSet::kCtest); }, 2);
  CHECK(gated.met());
  CHECK(runs == 1);
}
