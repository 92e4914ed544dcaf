// vt_bench SUITE [--json] [--quick]   or   vt_bench micro [Google Benchmark flags]
#include <benchmark/benchmark.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "bench.hpp"

namespace vt::bench {

namespace {
std::vector<Suite>& registry() {
  static std::vector<Suite> all;
  return all;
}
}  // namespace

bool registerSuite(const Suite& suite) {
  registry().push_back(suite);
  return true;
}
const std::vector<Suite>& suites() { return registry(); }

}  // namespace vt::bench

int main(int argc, char** argv) {
  const std::string name = argc > 1 ? argv[1] : "";
  if (name == "micro") {
    // Google Benchmark micro-benchmarks; pass e.g. --benchmark_format=json.
    argv[1] = argv[0];
    int count = argc - 1;
    benchmark::Initialize(&count, argv + 1);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
  }
  for (const auto& suite : vt::bench::suites()) {
    if (suite.name != name) continue;
    vt::bench::SuiteOptions options;
    for (int i = 2; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--json") options.json = true;
      else if (arg == "--quick") options.quick = true;
      else if (arg == "--check") options.check = true;
      else if (arg == "--plot" && i + 1 < argc) options.plot = argv[++i];
      else {
        std::fprintf(stderr, "vt_bench %s: unknown option '%s'\n", name.c_str(), arg.c_str());
        return 2;
      }
    }
    try {
      return suite.run(options);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "vt_bench %s: error: %s\n", name.c_str(), e.what());
      return 1;
    }
  }
  std::printf("usage: vt_bench SUITE [--json] [--quick] [--check] [--plot FILE.png] | vt_bench micro [--benchmark_* flags]\nsuites:\n");
  for (const auto& suite : vt::bench::suites()) {
    std::printf("  %-10.*s %.*s\n", int(suite.name.size()), suite.name.data(), int(suite.summary.size()),
                suite.summary.data());
  }
  return name.empty() ? 0 : 2;
}
