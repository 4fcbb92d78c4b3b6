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

}  // namespace

int main(int argc, char** argv) {
  using namespace vegstream;
  CLI::App cli{"vegstream: fly over real terrain covered with procedurally grown vegetation"};
  cli.require_subcommand(1);
  bool verbose = false;
  cli.add_flag("-v,--verbose", verbose, "More log output");

  app::FlyOptions fly;
  fly.samplesDir = app::samplesDirFromEnvironment(VEGSTREAM_SAMPLES_DIR);
  std::string size = "640x360";
  auto* flyCmd = cli.add_subcommand("fly", "Fly over a dataset: a window when a display exists, else PNG frames");
  flyCmd->add_option(
      "dataset", fly.dataset,
      "Dataset directory (vegstream import); default: the Zion sample, imported once into out/datasets/zion "
      "(without it: the synthetic dataset, generated once into out/datasets/synthetic)");
  flyCmd->add_option("--path", fly.path, "Flight path JSON; default: the benchmark-30s template over the dataset");
  flyCmd->add_option("--out", fly.out, "Directory for headless frames and run.json")->capture_default_str();
  flyCmd->add_option("--frames", fly.frames, "Number of headless frames")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  flyCmd->add_option("--size", size, "Frame size WxH")->capture_default_str();
  flyCmd->add_option("--msaa", fly.msaa, "Samples per pixel (1, 4, 8 where the device offers them)")
      ->capture_default_str();
  app::addFramesInFlightOption(*flyCmd, fly.framesInFlight);
  flyCmd->add_option("--device", fly.device, "Use the GPU whose name contains NAME (see `vegstream devices`)");
  flyCmd->add_flag("--validate", fly.validate, "Turn on the Vulkan validation layers");
  flyCmd->add_flag("--headless", fly.headless, "Never open a window, even when a display exists");
  app::addStreamingOptions(*flyCmd, fly.streaming, true);
  app::addSimulationOptions(*flyCmd, fly.simulationCli);
  app::addTreeOptions(*flyCmd, fly.treeCli);
  app::addSunOptions(*flyCmd, fly.sunCli);

  app::ImportOptions importOptions;
  auto* importCmd = app::addImportCommand(cli, importOptions);

  app::RecordOptions recordOptions;
  recordOptions.samplesDir = app::samplesDirFromEnvironment(VEGSTREAM_SAMPLES_DIR);
  auto* recordCmd = app::addRecordCommand(cli, recordOptions);
  app::ReportOptions reportOptions;
  auto* reportCmd = app::addReportCommand(cli, reportOptions);
  app::CompareOptions compareOptions;
  auto* compareCmd = app::addCompareCommand(cli, compareOptions);
  app::PathOptions pathOptions;
  auto* pathCmd = app::addPathCommand(cli, pathOptions);

  auto* devicesCmd = cli.add_subcommand("devices", "List the Vulkan devices vegstream can draw with");

  app::InfoOptions info;
  auto* infoCmd = cli.add_subcommand("info", "Describe a dataset directory as JSON (bounds, zooms, heights, tiles)");
  infoCmd->add_option("dataset", info.dataset, "Dataset directory")->required();

  app::QueryOptions query;
  auto* queryCmd = cli.add_subcommand("query", "Height, base colour and species of a dataset at one point, as JSON");
  queryCmd->add_option("dataset", query.dataset, "Dataset directory")->required();
  queryCmd->add_option("--lat", query.latDeg, "Latitude, degrees (WGS 84)")->required()->check(CLI::Range(-90.0, 90.0));
  queryCmd->add_option("--lon", query.lonDeg, "Longitude, degrees (WGS 84)")
      ->required()
      ->check(CLI::Range(-180.0, 180.0));
  queryCmd->add_option("--species", query.speciesFile,
                       "Species catalog JSON (default: the embedded config/species.json)");

  app::PlantsOptions plantsOptions;
  auto* plantsCmd = app::addPlantsCommand(cli, plantsOptions);
  app::InspectOptions inspectOptions;
  auto* inspectCmd = app::addInspectCommand(cli, inspectOptions);
  app::SnapshotOptions snapshotOptions;
  snapshotOptions.samplesDir = app::samplesDirFromEnvironment(VEGSTREAM_SAMPLES_DIR);
  auto* snapshotCmd = app::addSnapshotCommand(cli, snapshotOptions);

  datasets::SyntheticOptions gen;
  std::string genOut, genEncoding = "terrarium";
  auto* generateCmd = cli.add_subcommand("generate", "Write a synthetic dataset: fractal relief, biome colours");
  generateCmd->add_option("--out", genOut, "Dataset directory to create")->required();
  generateCmd->add_option("--lat", gen.centreLatDeg, "Latitude of the centre")->capture_default_str();
  generateCmd->add_option("--lon", gen.centreLonDeg, "Longitude of the centre")->capture_default_str();
  generateCmd->add_option("--size-km", gen.sizeKm, "Side of the square area, km")->capture_default_str();
  generateCmd->add_option("--seed", gen.seed, "Seed: the same seed gives identical files")->capture_default_str();
  generateCmd->add_option("--name", gen.name, "Dataset name (default: the --out directory's name)");
  generateCmd->add_option("--max-zoom", gen.maxZoom, "Finest zoom (default: pixels of at most 10 m)");
  generateCmd->add_option("--min-zoom", gen.minZoom, "Coarsest zoom (default: the area in one tile)");
  generateCmd->add_option("--encoding", genEncoding, "Elevation encoding: terrarium or terrain-rgb")
      ->capture_default_str();

  const auto runCommand = [&](const Logger& log) -> int {
    if (*devicesCmd) return listDevicesCommand(log);
    if (*recordCmd) return app::runRecord(recordOptions, log);
    if (*reportCmd) return app::runReport(reportOptions, log);
    if (*compareCmd) return app::runCompare(compareOptions, log);
    if (*pathCmd) return app::runPath(pathOptions, log);
    if (*importCmd) return app::runImport(importOptions, log);
    if (*infoCmd) return app::runInfo(info, log);
    if (*queryCmd) return app::runQuery(query, log);
    if (*plantsCmd) return app::runPlants(plantsOptions, log);
    if (*inspectCmd) return app::runInspect(inspectOptions, log);
    if (*snapshotCmd) return app::runSnapshot(snapshotOptions, log);
    if (*generateCmd) {
      auto encoding = datasets::parseElevationEncoding(genEncoding);
      if (!encoding) return app::reportError(log, encoding.error());
      gen.encoding = *encoding;
      gen.out = genOut;
      return app::runGenerate(gen, log);
    }
    if (*flyCmd) {
      if (!vegstream::app::parseFrameSize(size, fly.width, fly.height)) {
        log->error("--size {}: expected WxH with each side 1 … 16384, e.g. 640x360", size);
        return app::kExitUserError;
      }
      if (fly.msaa != 1 && fly.msaa != 2 && fly.msaa != 4 && fly.msaa != 8 && fly.msaa != 16) {
        log->error("--msaa {}: samples per pixel must be 1, 2, 4, 8 or 16", fly.msaa);
        return app::kExitUserError;
      }
      fly.framesGiven = flyCmd->count("--frames") > 0;
      return app::runFly(fly, log);
    }
    return app::kExitUserError;
  };

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
    return runCommand(log);
  } catch (const std::exception& e) {
    log->error("internal error (a bug in vegstream): {}", app::oneLine(e.what()));
  } catch (...) {
    log->error("internal error (a bug in vegstream): an unknown exception");
  }
  return app::kExitFailure;
}
