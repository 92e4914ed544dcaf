#pragma once
// Registry of benchmark suites. A suite measures one area and prints a single JSON object
// of figures (the numbers docs/PERFORMANCE.md quotes) or a readable table.
#include <string>
#include <string_view>
#include <vector>

namespace vt::bench {

struct SuiteOptions {
  bool json = false;   // print one JSON object on stdout
  bool quick = false;  // smaller sizes, for smoke tests in CI
  bool check = false;  // exit 1 when a correctness goal the suite defines is missed (ctest)
  std::string plot;    // --plot FILE.png: the suite's figure, when it draws one
};

struct Suite {
  std::string_view name;
  std::string_view summary;
  int (*run)(const SuiteOptions& options);
};

bool registerSuite(const Suite& suite);
const std::vector<Suite>& suites();

}  // namespace vt::bench

/// VT_BENCH_SUITE(haptics, "BVH, queries and haptic tick") { ...; return 0; }
#define VT_BENCH_SUITE(NAME, SUMMARY)                                                         \
  static int vtBenchSuite_##NAME(const ::vt::bench::SuiteOptions& options);                  \
  [[maybe_unused]] static const bool vtBenchRegistered_##NAME =                              \
      ::vt::bench::registerSuite({#NAME, SUMMARY, &vtBenchSuite_##NAME});                     \
  static int vtBenchSuite_##NAME(const ::vt::bench::SuiteOptions& options)
