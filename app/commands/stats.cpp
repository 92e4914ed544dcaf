// `vtouching stats`: the paper's Table I (V_scale, V_mean, V_std per object) for a dataset.
#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "cli.hpp"
#include "vt/acquisition/statistics.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"

namespace {

void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) vt::fail("stats: cannot write '", path.string(), "'");
}

}  // namespace

VT_COMMAND(stats, "stats DATASET_DIR [--out DIR] [--quiet]",
           "Table-I statistics (V_scale, V_mean, V_std) per object; writes statistics.csv/.json") {
  const auto outOption = args.value("out");
  const bool quiet = args.flag("quiet");
  const auto positional = args.positionals();
  args.finish();
  if (positional.size() != 1) vt::fail("stats: expected one DATASET_DIR (see vtouching help)");
  const std::filesystem::path dir = positional[0];
  const auto rows = vt::acq::datasetStats(dir);
  if (!quiet) std::fputs(vt::acq::statsTable(rows).c_str(), stdout);

  std::filesystem::path outDir = outOption ? std::filesystem::path(*outOption) : dir;
  if (!outOption && access(dir.c_str(), W_OK) != 0) {
    vt::log::warn("stats: '", dir.string(), "' is read-only; pass --out DIR to save statistics.csv and statistics.json");
    return 0;
  }
  std::error_code ec;
  std::filesystem::create_directories(outDir, ec);
  writeText(outDir / "statistics.csv", vt::acq::statsCsv(rows));
  writeText(outDir / "statistics.json", vt::acq::statsJson(rows));
  if (!quiet) std::printf("wrote %s and %s\n", (outDir / "statistics.csv").c_str(), (outDir / "statistics.json").c_str());
  return 0;
}
