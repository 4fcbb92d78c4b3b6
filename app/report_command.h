#pragma once
// `vegstream report DIR`: (re)makes a recording's summary.json from its frames.csv and
// recording.json, and its plots (flight/report.h).

#include <string>

#include "core/log.h"

namespace CLI {
class App;
}

namespace vegstream::app {

struct ReportOptions {
  std::string dir;
};

CLI::App* addReportCommand(CLI::App& cli, ReportOptions& options);

// Exit code: 0 done; 2 not a recording directory / bad frames.csv (one message); 1 the plots
// could not be made (python3 or matplotlib missing: the message says which), summary written.
int runReport(const ReportOptions& options, const Logger& log);

}  // namespace vegstream::app
