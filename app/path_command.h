#pragma once
// `vegstream path --dataset D --template NAME --out P.json`: a flight path made from a template
// (flight/path_templates.h) over a dataset's extent, with the dataset's heights as the ground,
// written atomically as flight-path JSON that `record` and `fly --path` read.

#include <string>

#include "core/log.h"

namespace CLI {
class App;
}

namespace vegstream::app {

struct PathOptions {
  std::string dataset;
  std::string templateName = "benchmark-30s";
  std::string out;
};

CLI::App* addPathCommand(CLI::App& cli, PathOptions& options);

// Exit code: 0 done; 2 a user mistake (missing dataset, unknown template; one message, nothing
// written); 1 an I/O failure.
int runPath(const PathOptions& options, const Logger& log);

}  // namespace vegstream::app
