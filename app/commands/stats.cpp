// `vtouching stats`: the paper's Table I (V_scale, V_mean, V_std per object) for a dataset.
#include <unistd.h>

#include <cstdio>

#include "cli.hpp"
#include "vt/acquisition/statistics.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/core/output_file.hpp"

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

  const std::filesystem::path outDir = outOption ? std::filesystem::path(*outOption) : dir;
  // Permission bits, not access(): root may write anywhere, but a folder nobody may write
  // to (like the shared published dataset) is not ours to add files to.
  std::error_code ec;
  const auto perms = std::filesystem::status(dir, ec).permissions();
  const auto anyWrite = std::filesystem::perms::owner_write | std::filesystem::perms::group_write |
                        std::filesystem::perms::others_write;
  if (!outOption && (ec || (perms & anyWrite) == std::filesystem::perms::none || access(dir.c_str(), W_OK) != 0)) {
    vt::log::warn("stats: '", dir.string(), "' is read-only; pass --out DIR to save statistics.csv and statistics.json");
    return 0;
  }
  std::filesystem::create_directories(outDir, ec);
  // Derived from the dataset, so re-running refreshes them; each is replaced whole or not at all.
  vt::writeFileAtomically(outDir / "statistics.csv", vt::acq::statsCsv(rows));
  vt::writeFileAtomically(outDir / "statistics.json", vt::acq::statsJson(rows));
  if (!quiet) std::printf("wrote %s and %s\n", (outDir / "statistics.csv").c_str(), (outDir / "statistics.json").c_str());
  return 0;
}
