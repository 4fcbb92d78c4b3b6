// `vegstream report` (report_command.h).

#include "app/report_command.h"

#include <CLI/CLI.hpp>

#include "app/exit_codes.h"
#include "flight/report.h"
#include "flight/summary.h"

namespace vegstream::app {

CLI::App* addReportCommand(CLI::App& cli, ReportOptions& o) {
  auto* cmd = cli.add_subcommand("report", "Remake a recording's summary.json and plots from its frames.csv");
  cmd->add_option("dir", o.dir, "Recording directory (vegstream record --out)")->required();
  return cmd;
}

int runReport(const ReportOptions& o, const Logger& log) {
  if (Status s = flight::writeSummary(o.dir); !s) return reportError(log, s.error());
  if (Status s = flight::makePlots(o.dir, flight::defaultPythons()); !s) {
    log->error("{} (summary.json was written)", s.error().message);
    return kExitFailure;
  }
  log->info("summary.json and {} plots written to {}", flight::reportPlotNames().size(), o.dir);
  return kExitOk;
}

}  // namespace vegstream::app
