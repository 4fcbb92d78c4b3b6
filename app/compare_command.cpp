// `vegstream compare` (compare_command.h).

#include "app/compare_command.h"

#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "app/exit_codes.h"
#include "flight/compare.h"
#include "flight/report.h"

namespace vegstream::app {
namespace fs = std::filesystem;

CLI::App* addCompareCommand(CLI::App& cli, CompareOptions& o) {
  auto* cmd = cli.add_subcommand("compare", "Two recordings side by side: B/A ratios and an overlay plot");
  cmd->add_option("dir_a", o.dirA, "Recording directory A (the reference)")->required();
  cmd->add_option("dir_b", o.dirB, "Recording directory B")->required();
  cmd->add_option("--out", o.out, "Overlay plot PNG (default: DIR_B/compare.png)");
  return cmd;
}

int runCompare(const CompareOptions& o, const Logger& log) {
  auto rows = flight::compareRecordings(o.dirA, o.dirB);
  if (!rows) return reportError(log, rows.error());
  std::cout << flight::formatCompareTable(*rows, o.dirA, o.dirB) << std::flush;
  const fs::path out = o.out.empty() ? fs::path(o.dirB) / "compare.png" : fs::path(o.out);
  if (Status s = flight::makeComparePlot(o.dirA, o.dirB, out, flight::defaultPythons()); !s) {
    log->error("{}", s.error().message);
    return kExitFailure;
  }
  log->info("overlay plot written to {}", out.string());
  return kExitOk;
}

}  // namespace vegstream::app
