// vt_bench SUITE [--json] [--quick] [--check] [--out results/NAME.json]   or   vt_bench micro [Google Benchmark flags]
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "bench.hpp"
#include "results_file.hpp"
#include "vt/core/error.hpp"
#include "vt/core/output_file.hpp"

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

namespace {

// Points stdout (fd 1, so printf, iostreams and child processes alike) at a temporary file until
// destroyed, then echoes what was written there, so --out shows the same as a plain run.
class CapturedStdout {
 public:
  CapturedStdout() : m_file(std::tmpfile()) {
    if (!m_file) fail("vt_bench: cannot create a temporary file for the suite's output");
    flushAll();
    m_saved = dup(STDOUT_FILENO);
    if (m_saved < 0 || dup2(fileno(m_file), STDOUT_FILENO) < 0) fail("vt_bench: cannot redirect stdout");
  }
  ~CapturedStdout() { release(); }
  CapturedStdout(const CapturedStdout&) = delete;
  CapturedStdout& operator=(const CapturedStdout&) = delete;

  /// Restores stdout and returns everything the suite printed (echoed to stdout as well).
  std::string release() {
    if (!m_file) return m_text;
    flushAll();
    dup2(m_saved, STDOUT_FILENO);
    close(m_saved);
    std::rewind(m_file);
    char buffer[4096];
    while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, m_file)) m_text.append(buffer, n);
    std::fclose(m_file);
    m_file = nullptr;
    std::fwrite(m_text.data(), 1, m_text.size(), stdout);
    return m_text;
  }

 private:
  static void flushAll() {
    std::cout.flush();
    std::fflush(stdout);
  }
  std::FILE* m_file;
  int m_saved = -1;
  std::string m_text;
};

// Runs the suite with --json and stores its figures, with where and how they were measured, in
// `out` (docs/PERFORMANCE.md, "How a table is backed").
int runToResultsFile(const Suite& suite, SuiteOptions options, const std::filesystem::path& out, int argc, char** argv) {
  options.json = true;
  RunRecord run;
  run.argv.assign(argv, argv + argc);
  run.date = utcNow();
  run.loadBefore = loadAverage();
  const auto start = std::chrono::steady_clock::now();
  std::string printed;
  {
    CapturedStdout capture;
    run.exitCode = suite.run(options);
    printed = capture.release();
  }
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.loadAfter = loadAverage();
  const std::string name(suite.name);
  const auto doc = resultsDocument(name, run, figuresFromOutput(name, printed), VT_SOURCE_DIR);
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  writeFileAtomically(out, doc.dump(2) + "\n");
  std::fprintf(stderr, "vt_bench %s: results in %s\n", name.c_str(), out.c_str());
  return run.exitCode;
}

}  // namespace
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
    std::string out;
    for (int i = 2; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--json") options.json = true;
      else if (arg == "--quick") options.quick = true;
      else if (arg == "--check") options.check = true;
      else if (arg == "--plot" && i + 1 < argc) options.plot = argv[++i];
      else if (arg == "--out" && i + 1 < argc) out = argv[++i];
      else {
        std::fprintf(stderr, "vt_bench %s: unknown option '%s'\n", name.c_str(), arg.c_str());
        return 2;
      }
    }
    try {
      return out.empty() ? suite.run(options) : vt::bench::runToResultsFile(suite, options, out, argc, argv);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "vt_bench %s: error: %s\n", name.c_str(), e.what());
      return 1;
    }
  }
  std::printf("usage: vt_bench SUITE [--json] [--quick] [--check] [--plot FILE.png] [--out results/NAME.json] | vt_bench micro [--benchmark_* flags]\nsuites:\n");
  for (const auto& suite : vt::bench::suites()) {
    std::printf("  %-10.*s %.*s\n", int(suite.name.size()), suite.name.data(), int(suite.summary.size()),
                suite.summary.data());
  }
  return name.empty() ? 0 : 2;
}
