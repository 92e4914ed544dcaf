// Acquisition throughput: a 100 x 100 mm synthetic scan (50 lines x 8 passes, ~1.2 M
// accelerometer rows) from scan directory to written dataset entry.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>
#include <thread>

#include <nlohmann/json.hpp>

#include "bench.hpp"
#include "vt/acquisition/pipeline.hpp"
#include "vt/acquisition/synthetic.hpp"

VT_BENCH_SUITE(acquire, "pixel-to-taxel pipeline on a 100 x 100 mm synthetic scan") {
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / "vt_acquire_bench";
  fs::remove_all(root);
  vt::acq::SyntheticOptions o;
  o.kind = vt::acq::SyntheticKind::ReliefCeramicTile;
  if (options.quick) o.lines = 10;
  vt::acq::writeSyntheticScan(o, root / "scan");

  using Clock = std::chrono::steady_clock;
  const int repeats = options.quick ? 1 : 5;
  double best = 1e9, bestAcquire = 1e9;
  std::size_t taxels = 0, rows = 0;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = Clock::now();
    const vt::acq::Scan scan = vt::acq::loadScan(root / "scan");
    const vt::acq::AcquireResult result = vt::acq::acquire(scan);
    const auto t1 = Clock::now();
    vt::acq::writeDataset(result, root / "dataset");
    const auto t2 = Clock::now();
    best = std::min(best, std::chrono::duration<double>(t2 - t0).count());
    bestAcquire = std::min(bestAcquire, std::chrono::duration<double>(t1 - t0).count());
    taxels = 0;
    for (const auto& line : result.lines) taxels += line.taxels.size();
    rows = 0;
    for (const auto& line : result.lines)
      for (const auto& pass : line.passes) rows += pass.j2 - pass.j1 + 1;
  }
  // The same logs as .npy arrays (docs/scan-format.md): reading every line both ways.
  const vt::acq::Scan scan = vt::acq::loadScan(root / "scan");
  std::vector<vt::acq::LineFiles> npyLines;
  for (std::size_t i = 0; i < scan.lines.size(); ++i) {
    const vt::acq::LineLogs logs = vt::acq::loadLine(scan.lines[i], scan.config);
    vt::acq::LineFiles files{root / ("robot_" + std::to_string(i) + ".npy"), root / ("accel_" + std::to_string(i) + ".npy")};
    std::ofstream(files.robot, std::ios::binary) << vt::acq::formatLogNpy(logs.robot);
    std::ofstream(files.accel, std::ios::binary) << vt::acq::formatLogNpy(logs.accel);
    npyLines.push_back(files);
  }
  auto readAll = [&](const std::vector<vt::acq::LineFiles>& lines) {
    double fastest = 1e9;
    for (int i = 0; i < repeats; ++i) {
      const auto t0 = Clock::now();
      for (const auto& line : lines) vt::acq::loadLine(line, scan.config);
      fastest = std::min(fastest, std::chrono::duration<double>(Clock::now() - t0).count());
    }
    return fastest;
  };
  const double csvRead = readAll(scan.lines), npyRead = readAll(npyLines);
  std::uintmax_t bytes = 0;
  for (const auto& e : fs::recursive_directory_iterator(root / "scan"))
    if (e.is_regular_file()) bytes += e.file_size();
  fs::remove_all(root);

  nlohmann::json out;
  out["scan_seconds"] = best;
  out["acquire_seconds"] = bestAcquire;
  out["taxels"] = taxels;
  out["taxels_per_s"] = double(taxels) / best;
  out["accel_samples_in_windows"] = rows;
  out["scan_mb"] = double(bytes) / 1e6;
  out["log_read_csv_s"] = csvRead;
  out["log_read_npy_s"] = npyRead;
  out["lines"] = o.lines;
  out["passes"] = o.passes;
  out["threads"] = std::max(1u, std::thread::hardware_concurrency());
  if (options.json) {
    std::printf("%s\n", out.dump().c_str());
  } else {
    std::printf("acquire: %d lines x %d passes, %.1f MB of logs: %.3f s (load + process %.3f s), %zu taxels, %.0f taxels/s\n",
                o.lines, o.passes, double(bytes) / 1e6, best, bestAcquire, taxels, double(taxels) / best);
  }
  return 0;
}
