// The results-file writer's parts (bench/results_file.hpp); a whole `vt_bench --out` run is the
// ctest bench.results_file_from_a_run.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "results_file.hpp"
#include "test_support.hpp"
#include "vt/core/error.hpp"

using vt::bench::figuresFromOutput;

TEST_CASE("The suite's figures are the first JSON object it printed, whatever surrounds it") {
  // A child process's line before, pretty-printed figures, the gate's verdict after.
  const std::string printed = "acquire: 50 lines {not json}\n{\n  \"a\": 1.5,\n  \"b\": {\"c\": [1, 2]}\n}\nevery goal met\n";
  const nlohmann::json figures = figuresFromOutput("demo", printed);
  CHECK(figures == nlohmann::json::parse(R"({"a": 1.5, "b": {"c": [1, 2]}})"));
  CHECK(figuresFromOutput("demo", "{\"x\": true}") == nlohmann::json::parse(R"({"x": true})"));
  CHECK_THROWS_WITH(figuresFromOutput("demo", "a table\nof text\n"), Catch::Contains("vt_bench demo") &&
                                                                     Catch::Contains("no JSON object"));
  CHECK_THROWS_AS(figuresFromOutput("demo", "[1, 2]\n"), vt::Error);  // figures are an object
}

TEST_CASE("A results document keeps the suite's figures untouched beside the run's provenance") {
  vt::bench::RunRecord run;
  run.argv = {"/some/build/bench/vt_bench", "haptics", "--quick", "--out", "results/h.json"};
  run.exitCode = 1;
  run.date = "2026-01-31T12:00:00Z";
  run.loadBefore = {1.5, 1.0, 0.5};
  run.loadAfter = {2.5, 1.2, 0.6};
  const auto figures = nlohmann::json::parse(R"({"ray_vs_embree": 1.02, "nested": {"k": "v"}})");
  const auto doc = vt::bench::resultsDocument("haptics", run, figures, vt::test::sourceDir());
  CHECK(doc["suite"] == "haptics");
  CHECK(doc["command"] == "vt_bench haptics --quick --out results/h.json");  // not the build folder's path
  CHECK(doc["exit_code"] == 1);
  CHECK(doc["load_average"]["before"][0] == 1.5);
  CHECK(doc["load_average"]["after"][0] == 2.5);
  CHECK(doc["figures"] == figures);
  CHECK(doc["build"]["type"].is_string());
  CHECK(doc["machine"]["logical_cores"].get<int>() >= 1);
  CHECK(doc["machine"]["cores_available"].get<int>() >= 1);
  CHECK(doc["machine"]["cpu_flags"].is_array());
  CHECK(doc.contains("source"));
  const auto load = vt::bench::loadAverage();
  CHECK(load[0] >= 0.0);
  CHECK(vt::bench::utcNow().size() == 20);
}

TEST_CASE("The source commit comes from git, and local changes to tracked files are flagged") {
  if (std::system("git --version >/dev/null 2>&1") != 0) VT_SKIP("git is not installed");
  // Outside the build tree, which may itself sit in a git checkout.
  std::string scratch = (std::filesystem::temp_directory_path() / "vt_results_git_XXXXXX").string();
  REQUIRE(mkdtemp(scratch.data()) != nullptr);
  const std::filesystem::path repo = scratch;
  CHECK(vt::bench::sourceInfo(repo)["commit"] == "unknown");  // not a repository
  const std::string git = "git -C '" + repo.string() + "' ";
  std::ofstream(repo / "a.txt") << "one\n";
  REQUIRE(std::system((git + "init -q && " + git + "add a.txt && " + git +
                       "-c user.name=t -c user.email=t@t commit -qm one").c_str()) == 0);
  auto source = vt::bench::sourceInfo(repo);
  CHECK(source["commit"].get<std::string>().size() == 40);
  CHECK(source["dirty"] == false);
  std::ofstream(repo / "untracked.json") << "{}\n";  // a fresh results file does not count
  CHECK(vt::bench::sourceInfo(repo)["dirty"] == false);
  std::ofstream(repo / "a.txt") << "two\n";
  CHECK(vt::bench::sourceInfo(repo)["dirty"] == true);
  std::filesystem::remove_all(repo);
}
