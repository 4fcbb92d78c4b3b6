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
#include "app/simulation_cli.h"
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

// Every subcommand's options, and its handle: true once the user chose it.
struct Commands {
  app::FlyOptions fly;
  std::string flySize = "640x360";
  CLI::App* flyCmd = nullptr;
  app::ImportOptions importOptions;
  CLI::App* importCmd = nullptr;
  app::RecordOptions recordOptions;
  CLI::App* recordCmd = nullptr;
  app::ReportOptions reportOptions;
  CLI::App* reportCmd = nullptr;
  app::CompareOptions compareOptions;
  CLI::App* compareCmd = nullptr;
  app::PathOptions pathOptions;
  CLI::App* pathCmd = nullptr;
  CLI::App* devicesCmd = nullptr;
  app::InfoOptions info;
  CLI::App* infoCmd = nullptr;
  app::QueryOptions query;
  CLI::App* queryCmd = nullptr;
  app::PlantsOptions plantsOptions;
  CLI::App* plantsCmd = nullptr;
  app::InspectOptions inspectOptions;
  CLI::App* inspectCmd = nullptr;
  app::SnapshotOptions snapshotOptions;
  CLI::App* snapshotCmd = nullptr;
  datasets::SyntheticOptions gen;
  std::string genOut, genEncoding = "terrarium";
  CLI::App* generateCmd = nullptr;
};

// `fly` and its options.
void addFlyCommand(CLI::App& cli, Commands& c) {
  c.fly.samplesDir = app::samplesDirFromEnvironment(VEGSTREAM_SAMPLES_DIR);
  c.flyCmd = cli.add_subcommand("fly", "Fly over a dataset: a window when a display exists, else PNG frames");
  c.flyCmd->add_option(
      "dataset", c.fly.dataset,
      "Dataset directory (vegstream import); default: the Zion sample, imported once into out/datasets/zion "
      "(without it: the synthetic dataset, generated once into out/datasets/synthetic)");
  c.flyCmd->add_option("--path", c.fly.path, "Flight path JSON; default: the benchmark-30s template over the dataset");
  c.flyCmd->add_option("--out", c.fly.out, "Directory for headless frames and run.json")->capture_default_str();
  c.flyCmd->add_option("--frames", c.fly.frames, "Number of headless frames")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  c.flyCmd->add_option("--size", c.flySize, "Frame size WxH")->capture_default_str();
  c.flyCmd->add_option("--msaa", c.fly.msaa, "Samples per pixel (1, 4, 8 where the device offers them)")
      ->capture_default_str();
  app::addFramesInFlightOption(*c.flyCmd, c.fly.framesInFlight);
  c.flyCmd->add_option("--device", c.fly.device, "Use the GPU whose name contains NAME (see `vegstream devices`)");
  c.flyCmd->add_flag("--validate", c.fly.validate, "Turn on the Vulkan validation layers");
  c.flyCmd->add_flag("--headless", c.fly.headless, "Never open a window, even when a display exists");
  app::addStreamingOptions(*c.flyCmd, c.fly.streaming, true);
  app::addSimulationOptions(*c.flyCmd, c.fly.simulationCli);
  app::addTreeOptions(*c.flyCmd, c.fly.treeCli);
  app::addSunOptions(*c.flyCmd, c.fly.sunCli);
}

// `info` and `query`, and their options.
void addInfoAndQueryCommands(CLI::App& cli, Commands& c) {
  c.infoCmd = cli.add_subcommand("info", "Describe a dataset directory as JSON (bounds, zooms, heights, tiles)");
  c.infoCmd->add_option("dataset", c.info.dataset, "Dataset directory")->required();
  c.queryCmd = cli.add_subcommand("query", "Height, base colour and species of a dataset at one point, as JSON");
  c.queryCmd->add_option("dataset", c.query.dataset, "Dataset directory")->required();
  c.queryCmd->add_option("--lat", c.query.latDeg, "Latitude, degrees (WGS 84)")
      ->required()
      ->check(CLI::Range(-90.0, 90.0));
  c.queryCmd->add_option("--lon", c.query.lonDeg, "Longitude, degrees (WGS 84)")
      ->required()
      ->check(CLI::Range(-180.0, 180.0));
  c.queryCmd->add_option("--species", c.query.speciesFile,
                         "Species catalog JSON (default: the embedded config/species.json)");
}

// `generate` and its options.
void addGenerateCommand(CLI::App& cli, Commands& c) {
  c.generateCmd = cli.add_subcommand("generate", "Write a synthetic dataset: fractal relief, biome colours");
  c.generateCmd->add_option("--out", c.genOut, "Dataset directory to create")->required();
  c.generateCmd->add_option("--lat", c.gen.centreLatDeg, "Latitude of the centre")->capture_default_str();
  c.generateCmd->add_option("--lon", c.gen.centreLonDeg, "Longitude of the centre")->capture_default_str();
  c.generateCmd->add_option("--size-km", c.gen.sizeKm, "Side of the square area, km")->capture_default_str();
  c.generateCmd->add_option("--seed", c.gen.seed, "Seed: the same seed gives identical files")->capture_default_str();
  c.generateCmd->add_option("--name", c.gen.name, "Dataset name (default: the --out directory's name)");
  c.generateCmd->add_option("--max-zoom", c.gen.maxZoom, "Finest zoom (default: pixels of at most 10 m)");
  c.generateCmd->add_option("--min-zoom", c.gen.minZoom, "Coarsest zoom (default: the area in one tile)");
  c.generateCmd->add_option("--encoding", c.genEncoding, "Elevation encoding: terrarium or terrain-rgb")
      ->capture_default_str();
}

// Every subcommand, in the order --help lists them.
void addCommands(CLI::App& cli, Commands& c) {
  addFlyCommand(cli, c);
  c.importCmd = app::addImportCommand(cli, c.importOptions);
  c.recordOptions.samplesDir = app::samplesDirFromEnvironment(VEGSTREAM_SAMPLES_DIR);
  c.recordCmd = app::addRecordCommand(cli, c.recordOptions);
  c.reportCmd = app::addReportCommand(cli, c.reportOptions);
  c.compareCmd = app::addCompareCommand(cli, c.compareOptions);
  c.pathCmd = app::addPathCommand(cli, c.pathOptions);
  c.devicesCmd = cli.add_subcommand("devices", "List the Vulkan devices vegstream can draw with");
  addInfoAndQueryCommands(cli, c);
  c.plantsCmd = app::addPlantsCommand(cli, c.plantsOptions);
  c.inspectCmd = app::addInspectCommand(cli, c.inspectOptions);
  c.snapshotOptions.samplesDir = app::samplesDirFromEnvironment(VEGSTREAM_SAMPLES_DIR);
  c.snapshotCmd = app::addSnapshotCommand(cli, c.snapshotOptions);
  addGenerateCommand(cli, c);
}

// `fly` after its own checks of --size and --msaa.
int runFly(Commands& c, const Logger& log) {
  app::FlyOptions& fly = c.fly;
  if (!vegstream::app::parseFrameSize(c.flySize, fly.width, fly.height)) {
    log->error("--size {}: expected WxH with each side 1 … 16384, e.g. 640x360", c.flySize);
    return app::kExitUserError;
  }
  if (fly.msaa != 1 && fly.msaa != 2 && fly.msaa != 4 && fly.msaa != 8 && fly.msaa != 16) {
    log->error("--msaa {}: samples per pixel must be 1, 2, 4, 8 or 16", fly.msaa);
    return app::kExitUserError;
  }
  fly.framesGiven = c.flyCmd->count("--frames") > 0;
  return app::runFly(fly, log);
}

// The subcommand the user chose.
int runCommand(Commands& c, const Logger& log) {
  if (*c.devicesCmd) return listDevicesCommand(log);
  if (*c.recordCmd) return app::runRecord(c.recordOptions, log);
  if (*c.reportCmd) return app::runReport(c.reportOptions, log);
  if (*c.compareCmd) return app::runCompare(c.compareOptions, log);
  if (*c.pathCmd) return app::runPath(c.pathOptions, log);
  if (*c.importCmd) return app::runImport(c.importOptions, log);
  if (*c.infoCmd) return app::runInfo(c.info, log);
  if (*c.queryCmd) return app::runQuery(c.query, log);
  if (*c.plantsCmd) return app::runPlants(c.plantsOptions, log);
  if (*c.inspectCmd) return app::runInspect(c.inspectOptions, log);
  if (*c.snapshotCmd) return app::runSnapshot(c.snapshotOptions, log);
  if (*c.generateCmd) {
    auto encoding = datasets::parseElevationEncoding(c.genEncoding);
    if (!encoding) return app::reportError(log, encoding.error());
    c.gen.encoding = *encoding;
    c.gen.out = c.genOut;
    return app::runGenerate(c.gen, log);
  }
  if (*c.flyCmd) return runFly(c, log);
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
