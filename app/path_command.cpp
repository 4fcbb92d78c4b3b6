// `vegstream path` (path_command.h). Reads heights point by point (DatasetReader), so it needs
// no GPU and loads only the tiles under the path.

#include "app/path_command.h"

#include <cmath>
#include <fstream>
#include <memory>

#include <CLI/CLI.hpp>

#include "app/exit_codes.h"
#include "core/atomic_file.h"
#include "datasets/dataset_reader.h"
#include "flight/flight_path_json.h"
#include "flight/path_templates.h"

namespace vegstream::app {
namespace fs = std::filesystem;

CLI::App* addPathCommand(CLI::App& cli, PathOptions& o) {
  std::string names;
  for (const auto& n : flight::templateNames()) names += (names.empty() ? "" : ", ") + n;
  auto* cmd = cli.add_subcommand("path", "Write a flight path made from a template over a dataset's area");
  cmd->add_option("--dataset", o.dataset, "Dataset directory (vegstream import / generate)")->required();
  cmd->add_option("--template", o.templateName, "Template: " + names)->capture_default_str();
  cmd->add_option("--out", o.out, "Flight path JSON to write")->required();
  return cmd;
}

int runPath(const PathOptions& o, const Logger& log) {
  auto reader = datasets::DatasetReader::open(o.dataset);
  if (!reader) return reportError(log, reader.error());
  auto shared = std::make_shared<datasets::DatasetReader>(std::move(*reader));
  // Unknown or unreadable ground is NaN (the templates then fly above the MSL datum).
  const flight::GroundHeight ground = [shared](double lat, double lon) {
    if (!shared->contains(lat, lon)) return std::nan("");
    auto h = shared->heightAt(lat, lon);
    return h ? *h : std::nan("");
  };
  auto path = flight::makePathFromTemplate(o.templateName, shared->meta().bounds, ground);
  if (!path) return reportError(log, path.error());
  const std::string text = flight::flightPathToJson(*path);
  if (Status s = writeTextAtomically(o.out, text); !s)
    return reportError(log, s.error());
  log->info("{}: {} over {} ({:.0f} s, {} keyframes)", o.out, o.templateName, shared->meta().name, path->duration(),
            path->keyframes.size());
  return kExitOk;
}

}  // namespace vegstream::app
