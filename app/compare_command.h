#pragma once
// `vegstream compare DIR_A DIR_B [--out PNG]`: prints the two recordings' summaries side by side
// with B/A ratios (stdout) and writes an overlay plot (default DIR_B/compare.png).

#include <string>

#include "core/log.h"

namespace CLI {
class App;
}

namespace vegstream::app {

struct CompareOptions {
  std::string dirA, dirB;
  std::string out;  // the overlay plot; empty: DIR_B/compare.png
};

CLI::App* addCompareCommand(CLI::App& cli, CompareOptions& options);

// Exit code: 0 done; 2 a directory without summary.json (one message); 1 the plot could not be
// made (the table is printed first).
int runCompare(const CompareOptions& options, const Logger& log);

}  // namespace vegstream::app
