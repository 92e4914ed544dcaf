// Acquisition throughput: a 100 x 100 mm synthetic scan (50 lines x 8 passes, ~1.2 M
// accelerometer rows) from scan directory to written dataset entry, and the same scan through
// tools/reference_pipeline.py (the paper's method in Python, issue 18's yardstick).
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>
#include <thread>

#include <nlohmann/json.hpp>

#include "bench.hpp"
#include "vt/acquisition/pipeline.hpp"
#include "vt/acquisition/synthetic.hpp"

namespace {

// A Python 3 with numpy (Debian's first: another python3 on PATH may lack it), or "".
std::string pythonWithNumpy() {
  for (const char* python : {"/usr/bin/python3", "python3"}) {
    const std::string probe = std::string(python) + " -c 'import numpy' >/dev/null 2>&1";
    const int status = std::system(probe.c_str());
    if (status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0) return python;
  }
  return "";
}

// CPU seconds (user + system, all threads) used so far by this process (RUSAGE_SELF) or by
// its waited-for children (RUSAGE_CHILDREN): unlike wall time, it hardly depends on how many
// other processes share the cores.
double cpuSeconds(int who) {
  rusage usage{};
  getrusage(who, &usage);
  const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

struct RunTime {
  double wall_s = 0, cpu_s = 0;
};

}  // namespace

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
  std::size_t taxels = 0, rows = 0;
  // Best of `repeats` (wall and CPU separately): loadScan + acquire, then writeDataset.
  struct ScanTimes {
    double total_s = 1e9, acquire_s = 1e9, cpu_s = 1e9;
  };
  const auto timeScan = [&](const fs::path& dir, const fs::path& dataset) {
    ScanTimes best;
    for (int i = 0; i < repeats; ++i) {
      const double cpu0 = cpuSeconds(RUSAGE_SELF);
      const auto t0 = Clock::now();
      const vt::acq::Scan scan = vt::acq::loadScan(dir);
      const vt::acq::AcquireResult result = vt::acq::acquire(scan);
      const auto t1 = Clock::now();
      vt::acq::writeDataset(result, dataset, true, /*replace=*/true);  // repeats replace the entry
      const auto t2 = Clock::now();
      best.cpu_s = std::min(best.cpu_s, cpuSeconds(RUSAGE_SELF) - cpu0);
      best.total_s = std::min(best.total_s, std::chrono::duration<double>(t2 - t0).count());
      best.acquire_s = std::min(best.acquire_s, std::chrono::duration<double>(t1 - t0).count());
      taxels = 0;
      for (const auto& line : result.lines) taxels += line.taxels.size();
      rows = 0;
      for (const auto& line : result.lines)
        for (const auto& pass : line.passes) rows += pass.j2 - pass.j1 + 1;
    }
    return best;
  };
  const ScanTimes csvScan = timeScan(root / "scan", root / "dataset");
  const double best = csvScan.total_s, bestAcquire = csvScan.acquire_s, bestCpu = csvScan.cpu_s;

  // The same scan with its logs as .npy arrays (docs/scan-format.md): a copy of the scan
  // directory whose scan.json names .npy logs, timed whole, and every line's logs read both ways.
  const vt::acq::Scan scan = vt::acq::loadScan(root / "scan");
  const fs::path npyDir = root / "scan_npy";
  fs::create_directories(npyDir / "lines");
  for (const char* file : {"photo.png", "calibration.csv"}) fs::copy_file(root / "scan" / file, npyDir / file);
  nlohmann::json npyJson = nlohmann::json::parse(std::ifstream(root / "scan" / "scan.json"));
  std::vector<vt::acq::LineFiles> npyLines;
  for (std::size_t i = 0; i < scan.lines.size(); ++i) {
    const vt::acq::LineLogs logs = vt::acq::loadLine(scan.lines[i], scan.config);
    const std::string robot = "lines/robot_" + std::to_string(i) + ".npy", accel = "lines/accel_" + std::to_string(i) + ".npy";
    vt::acq::LineFiles files{npyDir / robot, npyDir / accel};
    std::ofstream(files.robot, std::ios::binary) << vt::acq::formatLogNpy(logs.robot);
    std::ofstream(files.accel, std::ios::binary) << vt::acq::formatLogNpy(logs.accel);
    npyJson["lines"][i]["robot"] = robot;
    npyJson["lines"][i]["accel"] = accel;
    npyLines.push_back(files);
  }
  std::ofstream(npyDir / "scan.json") << npyJson.dump(2);
  const ScanTimes npyScan = timeScan(npyDir, root / "dataset_npy");
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

  // The reference: the paper's method re-run in Python on the same scan directory, as a
  // subprocess (interpreter start and numpy import included), with our calibration's
  // world -> pixel mapping (the script does not re-implement Zhang's method). One run each, wall
  // time: --style authors (the authors' per-sample and per-bin loops: issue 18's yardstick) and
  // --style numpy (a vectorised script). Both give our map (tests/acquisition/test_reference_pipeline.py).
  const std::string python = pythonWithNumpy();
  std::string referenceNote;
  const auto runReference = [&](const char* style) -> RunTime {
    if (python.empty()) {
      referenceNote = "skipped: no python3 with numpy (python3-numpy)";
      return {};
    }
    const fs::path object = root / "dataset" / std::string(vt::acq::kindName(o.kind));
    const std::string command = python + " '" VT_ASSETS_DIR "/../tools/reference_pipeline.py' '" + (root / "scan").string() +
                                "' '" + (object / (object.filename().string() + "_calibration.json")).string() + "' --out '" +
                                (root / "reference_map.npy").string() + "' --style " + style + " --quiet";
    const double cpu0 = cpuSeconds(RUSAGE_CHILDREN);
    const auto t0 = Clock::now();
    const int status = std::system(command.c_str());
    const RunTime run{std::chrono::duration<double>(Clock::now() - t0).count(), cpuSeconds(RUSAGE_CHILDREN) - cpu0};
    if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      referenceNote = "skipped: tools/reference_pipeline.py --style " + std::string(style) + " failed (exit status " +
                      std::to_string(status) + ")";
      return {};
    }
    return run;
  };
  const RunTime reference = runReference("authors");
  const RunTime numpyReference = reference.wall_s > 0 ? runReference("numpy") : RunTime{};
  std::uintmax_t bytes = 0;
  for (const auto& e : fs::recursive_directory_iterator(root / "scan"))
    if (e.is_regular_file()) bytes += e.file_size();
  fs::remove_all(root);

  nlohmann::json out;
  out["scan_seconds"] = best;
  out["acquire_seconds"] = bestAcquire;
  out["scan_cpu_seconds"] = bestCpu;
  out["scan_npy_seconds"] = npyScan.total_s;
  out["scan_npy_cpu_seconds"] = npyScan.cpu_s;
  out["taxels"] = taxels;
  out["taxels_per_s"] = double(taxels) / best;
  out["accel_samples_in_windows"] = rows;
  out["scan_mb"] = double(bytes) / 1e6;
  out["log_read_csv_s"] = csvRead;
  out["log_read_npy_s"] = npyRead;
  out["lines"] = o.lines;
  out["passes"] = o.passes;
  out["threads"] = std::max(1u, std::thread::hardware_concurrency());
  if (reference.wall_s > 0 && numpyReference.wall_s > 0) {
    out["reference_python_s"] = reference.wall_s;
    out["speedup_vs_reference"] = reference.wall_s / best;  // against load + process + write
    out["reference_python_cpu_s"] = reference.cpu_s;
    out["speedup_vs_reference_cpu"] = reference.cpu_s / bestCpu;
    out["reference_numpy_python_s"] = numpyReference.wall_s;
    out["speedup_vs_numpy_reference"] = numpyReference.wall_s / best;
    out["reference_numpy_python_cpu_s"] = numpyReference.cpu_s;
    out["speedup_vs_numpy_reference_cpu"] = numpyReference.cpu_s / bestCpu;
  } else {
    out["reference_note"] = referenceNote;
  }
  if (options.json) {
    std::printf("%s\n", out.dump().c_str());
  } else {
    std::printf("acquire: %d lines x %d passes, %.1f MB of logs: %.3f s (load + process %.3f s), %zu taxels, %.0f taxels/s\n",
                o.lines, o.passes, double(bytes) / 1e6, best, bestAcquire, taxels, double(taxels) / best);
    std::printf("  CPU time (all threads): %.3f s; the same scan with .npy logs: %.3f s (%.3f s CPU)\n", bestCpu,
                npyScan.total_s, npyScan.cpu_s);
    if (reference.wall_s > 0 && numpyReference.wall_s > 0) {
      for (const auto& [style, run] : {std::pair{"authors", reference}, std::pair{"numpy", numpyReference}}) {
        std::printf("reference (tools/reference_pipeline.py --style %s): %.2f s (%.2f s CPU), %.1fx slower than ours (%.1fx in CPU time)\n",
                    style, run.wall_s, run.cpu_s, run.wall_s / best, run.cpu_s / bestCpu);
      }
    } else {
      std::printf("reference: %s\n", referenceNote.c_str());
    }
  }
  return 0;
}
