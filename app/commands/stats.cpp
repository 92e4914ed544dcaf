// `vtouching stats`: the paper's Table I (V_scale, V_mean, V_std per object) for a dataset.
// Inputs are never written to: without --out the statistics go to stdout.
#include <cstdio>

#include "cli.hpp"
#include "vt/acquisition/statistics.hpp"
#include "vt/core/error.hpp"
#include "vt/core/output_file.hpp"

VT_COMMAND(stats) {
  const auto outOption = args.value("out");
  const bool json = args.flag("json");
  const bool quiet = args.flag("quiet");
  const auto positional = args.positionals();
  args.finish();
  if (positional.size() != 1) vt::fail("stats: expected one DATASET_DIR (see vtouching help)");
  const auto rows = vt::acq::datasetStats(positional[0]);
  if (!outOption) {
    std::fputs((json ? vt::acq::statsJson(rows) : vt::acq::statsCsv(rows)).c_str(), stdout);
    return 0;
  }
  const std::filesystem::path outDir = *outOption;
  std::error_code ec;
  std::filesystem::create_directories(outDir, ec);
  if (ec) vt::fail("stats: cannot create '", outDir.string(), "': ", ec.message());
  // Derived from the dataset, so re-running refreshes them; each is replaced whole or not at all.
  vt::writeFileAtomically(outDir / "statistics.csv", vt::acq::statsCsv(rows));
  vt::writeFileAtomically(outDir / "statistics.json", vt::acq::statsJson(rows));
  if (!quiet) {
    std::fputs(vt::acq::statsTable(rows).c_str(), stdout);
    std::printf("wrote %s and %s\n", (outDir / "statistics.csv").c_str(), (outDir / "statistics.json").c_str());
  }
  return 0;
}
