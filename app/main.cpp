// vegstream — fly over real terrain covered with procedurally grown vegetation.
// The command line: one subcommand per job (DESIGN.md, "Command line").

#include <iostream>
#include <regex>

#include <CLI/CLI.hpp>

#include "app/exit_codes.h"
#include "app/fly_command.h"
#include "app/generate_command.h"
#include "app/compare_command.h"
#include "app/import_command.h"
#include "app/info_command.h"
#include "app/inspect_command.h"
#include "app/parse_error_message.h"
#include "app/path_command.h"
#include "app/plants_command.h"
#include "app/record_command.h"
#include "app/report_command.h"
#include "app/sample_dataset.h"
#include "app/scene_setup.h"
#include "app/snapshot_command.h"
#include "app/query_command.h"
#include "core/log.h"
#include "render/context_options.h"

#ifndef VEGSTREAM_SAMPLES_DIR
#define VEGSTREAM_SAMPLES_DIR "../shared/datasets"
#endif

namespace {
using namespace vegstream;

int listDevicesCommand(const vegstream::Logger& log) {
  auto devices = vegstream::render::listDevices();
  if (!devices) return vegstream::app::reportError(log, devices.error());
  // No device is the system's problem (no driver installed or none that loads), not the user's.
  if (devices->empty())
    return vegstream::app::reportError(
        log, vegstream::makeError(vegstream::ErrorKind::Gpu, "no Vulkan device found (no driver loaded one)"));
  for (const auto& d : *devices)
    std::cout << d.index << ": " << d.name << " (" << d.type << ", " << d.driver << ", Vulkan " << d.apiVersion
              << ", MSAA " << d.msaaList() << ")\n";
  return vegstream::app::kExitOk;
}

// A subcommand's options, and its handle: true once the user chose it.
template <class Options>
struct Subcommand {
  Options options;
  CLI::App* cmd = nullptr;
};

// Every subcommand, with what it parses beyond its options.
struct Commands {
  Subcommand<app::FlyOptions> fly;
  std::string flySize = "640x360";
  Subcommand<app::ImportOptions> importing;
  Subcommand<app::RecordOptions> record;
  Subcommand<app::ReportOptions> report;
  Subcommand<app::CompareOptions> compare;
  Subcommand<app::PathOptions> path;
  CLI::App* devicesCmd = nullptr;
  Subcommand<app::InfoOptions> info;
  Subcommand<app::QueryOptions> query;
  Subcommand<app::PlantsOptions> plants;
  Subcommand<app::InspectOptions> inspect;
  Subcommand<app::SnapshotOptions> snapshot;
  Subcommand<datasets::SyntheticOptions> generate;
  std::string genOut, genEncoding = "terrarium";
};

// `fly` and its options.
void addFlyCommand(CLI::App& cli, Commands& c) {
  app::FlyOptions& o = c.fly.options;
  o.samplesDir = app::samplesDirFromEnvironment(VEGSTREAM_SAMPLES_DIR);
  c.fly.cmd = cli.add_subcommand("fly", "Fly over a dataset: a window when a display exists, else PNG frames");
  CLI::App& cmd = *c.fly.cmd;
  cmd.add_option("dataset", o.dataset,
                 "Dataset directory (vegstream import); default: the Zion sample, imported once into out/datasets/zion "
                 "(without it: the synthetic dataset, generated once into out/datasets/synthetic)");
  cmd.add_option("--path", o.path, "Flight path JSON; default: the benchmark-30s template over the dataset");
  cmd.add_option("--out", o.out, "Directory for headless frames and run.json")->capture_default_str();
  cmd.add_option("--frames", o.frames, "Number of headless frames")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  cmd.add_option("--size", c.flySize, "Frame size WxH")->capture_default_str();
  cmd.add_option("--msaa", o.msaa, "Samples per pixel (1, 4, 8 where the device offers them)")->capture_default_str();
  app::addFramesInFlightOption(cmd, o.framesInFlight);
  cmd.add_option("--device", o.device, "Use the GPU whose name contains NAME (see `vegstream devices`)");
  cmd.add_flag("--validate", o.validate, "Turn on the Vulkan validation layers");
  cmd.add_flag("--headless", o.headless, "Never open a window, even when a display exists");
  app::addSceneOptions(cmd, o.streaming, true, o.simulationCli, o.treeCli, o.sunCli);
}

// `info` and `query`, and their options.
void addInfoAndQueryCommands(CLI::App& cli, Commands& c) {
  c.info.cmd = cli.add_subcommand("info", "Describe a dataset directory as JSON (bounds, zooms, heights, tiles)");
  c.info.cmd->add_option("dataset", c.info.options.dataset, "Dataset directory")->required();
  c.query.cmd = cli.add_subcommand("query", "Height, base colour and species of a dataset at one point, as JSON");
  c.query.cmd->add_option("dataset", c.query.options.dataset, "Dataset directory")->required();
  c.query.cmd->add_option("--lat", c.query.options.latDeg, "Latitude, degrees (WGS 84)")
      ->required()
      ->check(CLI::Range(-90.0, 90.0));
  c.query.cmd->add_option("--lon", c.query.options.lonDeg, "Longitude, degrees (WGS 84)")
      ->required()
      ->check(CLI::Range(-180.0, 180.0));
  c.query.cmd->add_option("--species", c.query.options.speciesFile,
                          "Species catalog JSON (default: the embedded config/species.json)");
}

// `generate` and its options.
void addGenerateCommand(CLI::App& cli, Commands& c) {
  datasets::SyntheticOptions& o = c.generate.options;
  c.generate.cmd = cli.add_subcommand("generate", "Write a synthetic dataset: fractal relief, biome colours");
  CLI::App& cmd = *c.generate.cmd;
  cmd.add_option("--out", c.genOut, "Dataset directory to create")->required();
  cmd.add_option("--lat", o.centreLatDeg, "Latitude of the centre")->capture_default_str();
  cmd.add_option("--lon", o.centreLonDeg, "Longitude of the centre")->capture_default_str();
  cmd.add_option("--size-km", o.sizeKm, "Side of the square area, km")->capture_default_str();
  cmd.add_option("--seed", o.seed, "Seed: the same seed gives identical files")->capture_default_str();
  cmd.add_option("--name", o.name, "Dataset name (default: the --out directory's name)");
  cmd.add_option("--max-zoom", o.maxZoom, "Finest zoom (default: pixels of at most 10 m)");
  cmd.add_option("--min-zoom", o.minZoom, "Coarsest zoom (default: the area in one tile)");
  cmd.add_option("--encoding", c.genEncoding, "Elevation encoding: terrarium or terrain-rgb")->capture_default_str();
}

// Every subcommand, in the order --help lists them.
void addCommands(CLI::App& cli, Commands& c) {
  addFlyCommand(cli, c);
  c.importing.cmd = app::addImportCommand(cli, c.importing.options);
  c.record.options.samplesDir = app::samplesDirFromEnvironment(VEGSTREAM_SAMPLES_DIR);
  c.record.cmd = app::addRecordCommand(cli, c.record.options);
  c.report.cmd = app::addReportCommand(cli, c.report.options);
  c.compare.cmd = app::addCompareCommand(cli, c.compare.options);
  c.path.cmd = app::addPathCommand(cli, c.path.options);
  c.devicesCmd = cli.add_subcommand("devices", "List the Vulkan devices vegstream can draw with");
  addInfoAndQueryCommands(cli, c);
  c.plants.cmd = app::addPlantsCommand(cli, c.plants.options);
  c.inspect.cmd = app::addInspectCommand(cli, c.inspect.options);
  c.snapshot.options.samplesDir = app::samplesDirFromEnvironment(VEGSTREAM_SAMPLES_DIR);
  c.snapshot.cmd = app::addSnapshotCommand(cli, c.snapshot.options);
  addGenerateCommand(cli, c);
}

// `fly` after its own checks of --size and --msaa.
int runFly(Commands& c, const Logger& log) {
  app::FlyOptions& fly = c.fly.options;
  if (!vegstream::app::parseFrameSize(c.flySize, fly.width, fly.height)) {
    log->error("--size {}: expected WxH with each side 1 … 16384, e.g. 640x360", c.flySize);
    return app::kExitUserError;
  }
  if (fly.msaa != 1 && fly.msaa != 2 && fly.msaa != 4 && fly.msaa != 8 && fly.msaa != 16) {
    log->error("--msaa {}: samples per pixel must be 1, 2, 4, 8 or 16", fly.msaa);
    return app::kExitUserError;
  }
  fly.framesGiven = c.fly.cmd->count("--frames") > 0;
  return app::runFly(fly, log);
}

// The subcommand the user chose.
int runCommand(Commands& c, const Logger& log) {
  if (*c.devicesCmd) return listDevicesCommand(log);
  if (*c.record.cmd) return app::runRecord(c.record.options, log);
  if (*c.report.cmd) return app::runReport(c.report.options, log);
  if (*c.compare.cmd) return app::runCompare(c.compare.options, log);
  if (*c.path.cmd) return app::runPath(c.path.options, log);
  if (*c.importing.cmd) return app::runImport(c.importing.options, log);
  if (*c.info.cmd) return app::runInfo(c.info.options, log);
  if (*c.query.cmd) return app::runQuery(c.query.options, log);
  if (*c.plants.cmd) return app::runPlants(c.plants.options, log);
  if (*c.inspect.cmd) return app::runInspect(c.inspect.options, log);
  if (*c.snapshot.cmd) return app::runSnapshot(c.snapshot.options, log);
  if (*c.generate.cmd) {
    auto encoding = datasets::parseElevationEncoding(c.genEncoding);
    if (!encoding) return app::reportError(log, encoding.error());
    c.generate.options.encoding = *encoding;
    c.generate.options.out = c.genOut;
    return app::runGenerate(c.generate.options, log);
  }
  if (*c.fly.cmd) return runFly(c, log);
  return app::kExitUserError;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace vegstream;
  CLI::App cli{"vegstream: fly over real terrain covered with procedurally grown vegetation"};
  cli.require_subcommand(1);
  bool verbose = false;
  cli.add_flag("-v,--verbose", verbose, "More log output");
  Commands commands;  // CLI11 keeps pointers into it: it stays where it is
  addCommands(cli, commands);

  const Logger log = makeConsoleLogger("vegstream", spdlog::level::info);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help (and CLI11's other successes) print what was asked for, exit 0. Every other parse
    // error is a user mistake: one line naming the subcommand, the option and the problem, exit 2
    // (not cli.exit, which adds "Run with --help for more information.").
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return cli.exit(e);
    log->error("{}", app::parseErrorMessage(cli, e));
    return app::kExitUserError;
  }
  if (verbose) log->set_level(spdlog::level::debug);

  // Commands return errors as values; an exception reaching here is a bug, reported in one line
  // (exit 1) rather than left to end the program with a signal.
  try {
    return runCommand(commands, log);
  } catch (const std::exception& e) {
    log->error("internal error (a bug in vegstream): {}", app::oneLine(e.what()));
  } catch (...) {
    log->error("internal error (a bug in vegstream): an unknown exception");
  }
  return app::kExitFailure;
}
