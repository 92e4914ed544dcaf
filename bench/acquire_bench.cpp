// Acquisition throughput on a 100 x 100 mm synthetic scan (50 lines x 8 passes, ~1.2 M
// accelerometer rows), end to end as separate processes, interleaved, medians:
//  - ours: `vtouching acquire SCAN --out DATASET` with its default outputs (waveforms on), and
//    the same with --no-waveforms (a labelled extra column);
//  - the authors' own pipeline as they ship it (wmtlab/Pixel2Taxel Process_Code/run.py, their
//    loader of pickled per-line dicts) on the same scan in their raw layout
//    (tools/pixel2taxel_export.py), run by tools/run_pixel2taxel.py: the yardstick. Its checkout
//    is not part of this repository: VT_PIXEL2TAXEL_DIR names it, else the column is skipped;
//  - tools/reference_pipeline.py, our numpy re-run of the paper's method in two styles (a
//    second, labelled column; issue 18's yardstick).
// Plus in-process figures of the library (load + process + write, CSV and .npy logs).
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench.hpp"
#include "vt/acquisition/pipeline.hpp"
#include "vt/acquisition/synthetic.hpp"
#include "vt/acquisition/waveforms.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Debian's python3 first (another python3 on PATH may lack the modules) with `modules`, or "".
std::string pythonWith(const char* modules) {
  for (const char* python : {"/usr/bin/python3", "python3"}) {
    const std::string probe = std::string(python) + " -c 'import " + modules + "' >/dev/null 2>&1";
    const int status = std::system(probe.c_str());
    if (status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0) return python;
  }
  return "";
}

// CPU seconds (user + system, all threads) of this process (RUSAGE_SELF) or of its waited-for
// children (RUSAGE_CHILDREN): unlike wall time, it hardly depends on the other processes' load.
double cpuSeconds(int who) {
  rusage usage{};
  getrusage(who, &usage);
  const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

struct RunTime {
  double wall_s = 0, cpu_s = 0;
};

// Runs a shell command as a child process; its wall and CPU time, or nothing when it failed.
std::optional<RunTime> timeCommand(const std::string& command) {
  const double cpu0 = cpuSeconds(RUSAGE_CHILDREN);
  const auto t0 = Clock::now();
  const int status = std::system((command + " >/dev/null 2>&1").c_str());
  const RunTime run{std::chrono::duration<double>(Clock::now() - t0).count(), cpuSeconds(RUSAGE_CHILDREN) - cpu0};
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return std::nullopt;
  return run;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A path in single quotes for /bin/sh (the bench's paths hold no quote).
std::string shellQuoted(const fs::path& p) {
  std::string out = p.string();
  out.insert(out.begin(), '\'');
  out.push_back('\'');
  return out;
}

// One contestant of the interleaved end-to-end runs.
struct Column {
  std::string key;      // JSON prefix
  std::string label;    // what it is, for the table
  std::string command;  // empty: skipped
  std::string note;     // why skipped
  std::vector<double> wall, cpu;
};

// Median wall and CPU of each column and the ratios of the others' medians to ours, and the
// range of the per-round ratios (each round ran every column once, in rotating order).
void report(nlohmann::json& out, const std::vector<Column>& columns, int rounds) {
  const Column& ours = columns.front();
  for (const Column& c : columns) {
    if (c.command.empty() || c.wall.size() != std::size_t(rounds)) {
      out[c.key + "_note"] = c.note.empty() ? "failed (run the command by hand to see why)" : c.note;
      continue;
    }
    out[c.key + "_wall_s"] = median(c.wall);
    out[c.key + "_cpu_s"] = median(c.cpu);
    if (&c == &ours || ours.wall.size() != c.wall.size()) continue;
    out["speedup_vs_" + c.key + "_wall"] = median(c.wall) / median(ours.wall);
    out["speedup_vs_" + c.key + "_cpu"] = median(c.cpu) / median(ours.cpu);
    std::vector<double> wall, cpu;
    for (std::size_t i = 0; i < c.wall.size(); ++i) wall.push_back(c.wall[i] / ours.wall[i]), cpu.push_back(c.cpu[i] / ours.cpu[i]);
    out["speedup_vs_" + c.key + "_wall_range"] = {*std::min_element(wall.begin(), wall.end()), *std::max_element(wall.begin(), wall.end())};
    out["speedup_vs_" + c.key + "_cpu_range"] = {*std::min_element(cpu.begin(), cpu.end()), *std::max_element(cpu.begin(), cpu.end())};
  }
}

// In-process: loadScan + acquire + measureWaveforms (when `waveforms`) + writeDataset, medians.
struct InProcess {
  double wall_s = 0, cpu_s = 0;
  std::size_t taxels = 0, rows = 0;
};

InProcess timeInProcess(const fs::path& scanDir, const fs::path& dataset, int repeats, bool waveforms) {
  std::vector<double> wall, cpu;
  InProcess r;
  for (int i = 0; i < repeats; ++i) {
    const double cpu0 = cpuSeconds(RUSAGE_SELF);
    const auto t0 = Clock::now();
    const vt::acq::AcquireResult result = vt::acq::acquire(vt::acq::loadScan(scanDir), {.keepSamples = waveforms});
    const auto grid = waveforms ? std::optional(vt::acq::measureWaveforms(result)) : std::nullopt;
    vt::acq::writeDataset(result, dataset, true, /*replace=*/true, grid ? &*grid : nullptr);
    wall.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    cpu.push_back(cpuSeconds(RUSAGE_SELF) - cpu0);
    r.taxels = r.rows = 0;
    for (const auto& line : result.lines) {
      r.taxels += line.taxels.size();
      for (const auto& pass : line.passes) r.rows += pass.j2 - pass.j1 + 1;
    }
  }
  r.wall_s = median(wall), r.cpu_s = median(cpu);
  return r;
}

// A copy of the scan whose scan.json names .npy logs (docs/scan-format.md).
fs::path npyCopy(const fs::path& root, const fs::path& scanDir) {
  const vt::acq::Scan scan = vt::acq::loadScan(scanDir);
  const fs::path npyDir = root / "scan_npy";
  fs::create_directories(npyDir / "lines");
  for (const char* file : {"photo.png", "calibration.csv"}) fs::copy_file(scanDir / file, npyDir / file);
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(scanDir / "scan.json"));
  for (std::size_t i = 0; i < scan.lines.size(); ++i) {
    const vt::acq::LineLogs logs = vt::acq::loadLine(scan.lines[i], scan.config);
    const std::string robot = "lines/robot_" + std::to_string(i) + ".npy", accel = "lines/accel_" + std::to_string(i) + ".npy";
    std::ofstream(npyDir / robot, std::ios::binary) << vt::acq::formatLogNpy(logs.robot);
    std::ofstream(npyDir / accel, std::ios::binary) << vt::acq::formatLogNpy(logs.accel);
    doc["lines"][i]["robot"] = robot;
    doc["lines"][i]["accel"] = accel;
  }
  std::ofstream(npyDir / "scan.json") << doc.dump(2);
  return npyDir;
}

}  // namespace

VT_BENCH_SUITE(acquire, "pixel-to-taxel pipeline on a 100 x 100 mm scan against the authors' own pipeline") {
  const fs::path root = fs::temp_directory_path() / "vt_acquire_bench";
  fs::remove_all(root);
  vt::acq::SyntheticOptions o;
  o.kind = vt::acq::SyntheticKind::ReliefCeramicTile;
  o.authorsRig = true;  // the authors' camera orientation: their run.py draws its map (see tools/run_pixel2taxel.py)
  if (options.quick) o.lines = 10;
  const fs::path scanDir = root / "scan";
  vt::acq::writeSyntheticScan(o, scanDir);
  const int rounds = options.quick ? 1 : 5;
  const std::string tools = VT_ASSETS_DIR "/../tools/";

  // The end-to-end contestants, each a separate process.
  std::vector<Column> columns;
#ifdef VT_VTOUCHING
  const std::string ours = std::string("'") + VT_VTOUCHING + "' acquire " + shellQuoted(scanDir) + " --force --quiet --out ";
  columns.push_back({"ours", "vtouching acquire (default outputs: waveforms on)", ours + shellQuoted(root / "ours"), "", {}, {}});
  columns.push_back({"ours_no_waveforms", "vtouching acquire --no-waveforms", ours + shellQuoted(root / "ours_nw") + " --no-waveforms",
                     "", {}, {}});
#else
  columns.push_back({"ours", "vtouching acquire", "", "skipped: the vtouching target is not part of this build", {}, {}});
#endif
  const std::string python = pythonWith("numpy");
  const std::string pythonCv = pythonWith("numpy, cv2");
  const char* checkout = std::getenv("VT_PIXEL2TAXEL_DIR");
  Column authors{"authors", "the authors' run.py as shipped (their loader of pickled dicts), via tools/run_pixel2taxel.py", "", "", {}, {}};
  const fs::path raw = root / "raw";
  if (!checkout || !*checkout) {
    authors.note = "skipped: set VT_PIXEL2TAXEL_DIR to a checkout of wmtlab/Pixel2Taxel";
  } else if (!fs::is_regular_file(fs::path(checkout) / "Process_Code" / "run.py")) {
    authors.note = std::string("skipped: ") + checkout + "/Process_Code/run.py not found (VT_PIXEL2TAXEL_DIR)";
  } else if (pythonCv.empty()) {
    authors.note = "skipped: no python3 with numpy and cv2 (python3-numpy, python3-opencv)";
  } else if (!timeCommand(pythonCv + " " + shellQuoted(tools + "pixel2taxel_export.py") + " " + shellQuoted(scanDir) + " --out " + shellQuoted(raw))) {
    authors.note = "skipped: tools/pixel2taxel_export.py failed on the bench scan";
  } else {
    authors.command = pythonCv + " " + shellQuoted(tools + "run_pixel2taxel.py") + " " + shellQuoted(checkout) + " " + shellQuoted(raw) + " 1";
  }
  columns.push_back(authors);
  for (const char* style : {"authors", "numpy"}) {
    Column c{std::string("reference_") + style, std::string("tools/reference_pipeline.py --style ") + style + " (our numpy re-run)",
             "", "", {}, {}};
    if (python.empty()) c.note = "skipped: no python3 with numpy (python3-numpy)";
    columns.push_back(c);
  }

  // The references read our calibration: one run of ours first writes it (and warms the caches).
  const fs::path calibration = root / "ours" / "relief_ceramic_tile" / "relief_ceramic_tile_calibration.json";
  if (!columns.front().command.empty()) timeCommand(columns.front().command);
  for (Column& c : columns) {
    if (c.key.rfind("reference_", 0) != 0 || python.empty()) continue;
    if (!fs::exists(calibration)) {
      c.note = "skipped: no calibration from our run";
      continue;
    }
    c.command = python + " " + shellQuoted(tools + "reference_pipeline.py") + " " + shellQuoted(scanDir) + " " + shellQuoted(calibration) +
                " --out " + shellQuoted(root / (c.key + ".npy")) + " --style " + c.key.substr(10) + " --quiet";
  }
  if (!authors.command.empty()) timeCommand(authors.command);  // warm-up: the raw files in the page cache

  for (int round = 0; round < rounds; ++round) {
    for (std::size_t k = 0; k < columns.size(); ++k) {
      Column& c = columns[(k + std::size_t(round)) % columns.size()];  // rotating order
      if (c.command.empty()) continue;
      if (const auto run = timeCommand(c.command)) c.wall.push_back(run->wall_s), c.cpu.push_back(run->cpu_s);
    }
  }

  // In-process (no process start), medians of `rounds`.
  const InProcess csv = timeInProcess(scanDir, root / "inproc", rounds, true);
  const InProcess csvNoWaves = timeInProcess(scanDir, root / "inproc_nw", rounds, false);
  const InProcess npy = timeInProcess(npyCopy(root, scanDir), root / "inproc_npy", rounds, true);
  std::uintmax_t bytes = 0;
  for (const auto& e : fs::recursive_directory_iterator(scanDir))
    if (e.is_regular_file()) bytes += e.file_size();
  fs::remove_all(root);

  nlohmann::json out;
  out["lines"] = o.lines;
  out["passes"] = o.passes;
  out["scan_mb"] = double(bytes) / 1e6;
  out["taxels"] = csv.taxels;
  out["accel_samples_in_windows"] = csv.rows;
  out["rounds"] = rounds;
  out["threads"] = std::max(1u, std::thread::hardware_concurrency());
  report(out, columns, rounds);
  for (const auto& [key, run] : {std::pair{"inprocess", csv}, std::pair{"inprocess_no_waveforms", csvNoWaves},
                                 std::pair{"inprocess_npy", npy}}) {
    out[std::string(key) + "_seconds"] = run.wall_s;
    out[std::string(key) + "_cpu_seconds"] = run.cpu_s;
  }
  if (options.json) {
    std::printf("%s\n", out.dump().c_str());
    return 0;
  }
  std::printf("acquire: %d lines x %d passes, %.1f MB of CSV logs, %zu taxels; end to end as processes, medians of %d "
              "interleaved rounds:\n",
              o.lines, o.passes, double(bytes) / 1e6, csv.taxels, rounds);
  for (const Column& c : columns) {
    if (!out.contains(c.key + "_wall_s")) {
      std::printf("  %-20s %s\n", c.key.c_str(), out[c.key + "_note"].get<std::string>().c_str());
      continue;
    }
    std::printf("  %-20s %7.3f s wall %7.3f s CPU", c.key.c_str(), out[c.key + "_wall_s"].get<double>(),
                out[c.key + "_cpu_s"].get<double>());
    if (out.contains("speedup_vs_" + c.key + "_wall")) {
      std::printf("  (%.1fx ours in wall time, %.1fx in CPU time)", out["speedup_vs_" + c.key + "_wall"].get<double>(),
                  out["speedup_vs_" + c.key + "_cpu"].get<double>());
    }
    std::printf("  %s\n", c.label.c_str());
  }
  std::printf("in process: %.3f s (%.3f s CPU) with waveforms, %.3f s (%.3f s CPU) without, %.3f s (%.3f s CPU) with .npy logs\n",
              csv.wall_s, csv.cpu_s, csvNoWaves.wall_s, csvNoWaves.cpu_s, npy.wall_s, npy.cpu_s);
  return 0;
}
