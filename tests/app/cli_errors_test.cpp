// Command-line mistakes through the real executable (app/README.md, DESIGN.md "Command line"):
// every error CLI11 catches while parsing — a value out of range, not a number, an unknown
// option, a missing argument or value, an extra positional — is ONE non-empty line on stderr that
// names the option, exit code 2, nothing on stdout, for every subcommand; `--help` still prints
// the help and exits 0. None of these needs a GPU or a dataset: parsing fails before either is
// touched (the dataset arguments below do not exist, and nothing may be created).
// Also: no Vulkan device at all (no driver loads) is the system's failure, exit 1, one line.

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/run_command.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

// This test's own scratch directory, made fresh: VEGSTREAM_TEST_TMP/<suite>_<name>/.
fs::path ownDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(VEGSTREAM_TEST_TMP) / (std::string(info->test_suite_name()) + "_" + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

struct Mistake {
  std::string args;   // after `vegstream`
  std::string named;  // what the one line must name (the option, or the unexpected argument)
};

// The line states a problem, not just a name: one of the phrasings the parser and the commands use.
bool saysTheProblem(const std::string& err) {
  for (const char* phrase :
       {"not in range", "not in {", "is not a number", "is not a valid", "not expected", "is required", "required",
        "missing", "must be", "expected", "unknown subcommand", "does not exist", "no zone"})
    if (err.find(phrase) != std::string::npos) return true;
  return false;
}

// Runs each mistake in `dir` (so that a wrongly accepted command could only write there) and
// checks the contract; `prefix` is what the line must also say (the subcommand).
void expectOneLineUserErrors(const std::vector<Mistake>& mistakes, const std::string& prefix) {
  for (const Mistake& m : mistakes) {
    SCOPED_TRACE("vegstream " + m.args);
    const auto r = runVegstream(m.args);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find_first_not_of(" \n"), std::string::npos) << "the line is not empty";
    EXPECT_NE(r.err.find(m.named), std::string::npos) << "names " << m.named << ": " << r.err;
    EXPECT_NE(r.err.find(prefix), std::string::npos) << "names " << prefix << ": " << r.err;
    EXPECT_TRUE(saysTheProblem(r.err)) << r.err;
    EXPECT_EQ(r.err.find("--help for more"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST(CliErrors, Import) {
  const fs::path dir = ownDir(), out = dir / "out";
  const std::string o = " --out " + q(out);
  expectOneLineUserErrors({{"import --dem d.tif" + o + " --jpeg-quality 0", "--jpeg-quality"},
                           {"import --dem d.tif" + o + " --max-zoom 23", "--max-zoom"},
                           {"import --dem d.tif" + o + " --threads many", "--threads"},
                           {"import --dem d.tif" + o + " --bogus 1", "--bogus"},
                           {"import --dem d.tif", "--out"},
                           {"import --dem d.tif --out", "--out"},
                           {"import --dem d.tif" + o + " extra", "extra"}},
                          "vegstream import");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliErrors, Generate) {
  const fs::path dir = ownDir(), out = dir / "out";
  const std::string o = " --out " + q(out);
  expectOneLineUserErrors({{"generate" + o + " --seed x", "--seed"},
                           {"generate" + o + " --size-km ten", "--size-km"},
                           {"generate" + o + " --bogus", "--bogus"},
                           {"generate --seed 3", "--out"},
                           {"generate" + o + " --max-zoom", "--max-zoom"},
                           {"generate" + o + " extra", "extra"}},
                          "vegstream generate");
  // Out of range is checked after parsing, before anything is written: one line too.
  expectOneLineUserErrors({{"generate" + o + " --size-km 0", "--size-km"}}, "--size-km");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliErrors, Info) {
  const fs::path dir = ownDir(), d = dir / "no-dataset";
  expectOneLineUserErrors(
      {{"info", "dataset"}, {"info " + q(d) + " --bogus", "--bogus"}, {"info " + q(d) + " extra", "extra"}},
      "vegstream info");
}

TEST(CliErrors, Query) {
  const fs::path dir = ownDir(), d = dir / "no-dataset";
  const std::string ds = "query " + q(d);
  expectOneLineUserErrors({{ds + " --lat 91 --lon 0", "--lat"},
                           {ds + " --lat 0 --lon -181", "--lon"},
                           {ds + " --lat north --lon 0", "--lat"},
                           {ds + " --lat 0 --lon 1e", "--lon"},
                           {ds + " --lat 0 --lon 0 --bogus", "--bogus"},
                           {ds + " --lon 0", "--lat"},
                           {"query --lat 0 --lon 0", "dataset"},
                           {ds + " --lat 0 --lon", "--lon"},
                           {ds + " --lat 0 --lon 0 extra", "extra"}},
                          "vegstream query");
}

TEST(CliErrors, Plants) {
  const fs::path dir = ownDir(), d = dir / "no-dataset", out = dir / "plants.csv";
  const std::string ds = "plants " + q(d) + " --output " + q(out);
  expectOneLineUserErrors({{ds + " --bbox 0,0,1,1 --max-plants lots", "--max-plants"},
                           {ds + " --bbox 0,0,1,1 --cluster-size 2.5", "--cluster-size"},
                           {ds + " --bbox 0,0,1,1 --bogus", "--bogus"},
                           {ds, "--bbox"},
                           {ds + " --bbox", "--bbox"},
                           {ds + " --bbox 0,0,1,1 extra", "extra"}},
                          "vegstream plants");
  // Out of range is checked after parsing, before the dataset is opened: one line too.
  expectOneLineUserErrors({{ds + " --bbox 0,0,1,1 --cluster-size 33", "--cluster-size"}}, "--cluster-size");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliErrors, Fly) {
  const fs::path dir = ownDir(), d = dir / "no-dataset", out = dir / "frames";
  const std::string ds = "fly " + q(d) + " --headless --out " + q(out);
  expectOneLineUserErrors({{ds + " --frames 0", "--frames"},
                           {ds + " --frames many", "--frames"},
                           {ds + " --terrain-error-px two", "--terrain-error-px"},
                           {ds + " --streaming sometimes", "--streaming"},
                           {ds + " --terrain-shading sometimes", "--terrain-shading"},
                           {ds + " --occlusion-culling maybe", "--occlusion-culling"},
                           {ds + " --occlusion-culling", "--occlusion-culling"},
                           {ds + " --frames-in-flight 4", "--frames-in-flight"},
                           {ds + " --frames-in-flight 0", "--frames-in-flight"},
                           {ds + " --blade-path fancy", "--blade-path"},
                           {ds + " --bogus", "--bogus"},
                           {ds + " --path", "--path"},
                           {ds + " extra", "extra"}},
                          "vegstream fly");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliErrors, Record) {
  const fs::path dir = ownDir(), d = dir / "no-dataset", out = dir / "rec";
  const std::string ds = "record " + q(d) + " --path p.json --out " + q(out);
  expectOneLineUserErrors({{ds + " --fps 0", "--fps"},
                           {ds + " --warmup 601", "--warmup"},
                           {ds + " --fps sixty", "--fps"},
                           {ds + " --frames-every -1", "--frames-every"},
                           {ds + " --terrain-shading", "--terrain-shading"},
                           {ds + " --occlusion-culling 2", "--occlusion-culling"},
                           {ds + " --frames-in-flight 0", "--frames-in-flight"},
                           {ds + " --frames-in-flight 4", "--frames-in-flight"},
                           {ds + " --frames-in-flight two", "--frames-in-flight"},
                           {ds + " --blade-path", "--blade-path"},
                           {ds + " --blade-path hull", "--blade-path"},
                           {ds + " --bogus", "--bogus"},
                           {"record " + q(d) + " --out " + q(out), "--path"},
                           {"record " + q(d) + " --path p.json", "--out"},
                           {ds + " --device", "--device"},
                           {ds + " extra", "extra"}},
                          "vegstream record");
  EXPECT_FALSE(fs::exists(out));
}

// The simulation options (app/simulation_cli.h) are checked after parsing, before the path, the
// dataset or the GPU is touched: one line naming the option, exit 2, nothing written.
// Belyaev's contour term and the AOVs (issue 39): checked after parsing, on every command that has them.
TEST(CliErrors, ContourAndAovOptions) {
  const fs::path dir = ownDir(), d = dir / "no-dataset", rec = dir / "rec", frames = dir / "frames",
                 still = dir / "still.png";
  const std::string record = "record " + q(d) + " --path p.json --out " + q(rec);
  const std::string fly = "fly " + q(d) + " --headless --out " + q(frames);
  const std::string snapshot = "snapshot --lat 37.4 --lon -113 --alt 2 --heading 0 --pitch -10 --out " + q(still);
  for (const std::string& command : {record, fly, snapshot})
    expectOneLineUserErrors({{command + " --plant-contour -1", "--plant-contour -1: must be 0 (off) … 64"},
                             {command + " --plant-contour 65", "--plant-contour 65: must be"}},
                            "--");
  expectOneLineUserErrors({{record + " --aov depth", "--aov depth: --frames-every K is required"},
                           {record + " --frames-every 5 --aov colour", "--aov colour: no AOV named 'colour'"},
                           {snapshot + " --aov depth,", "--aov depth,: no AOV named ''"}},
                          "--");
  EXPECT_FALSE(fs::exists(rec));
  EXPECT_FALSE(fs::exists(frames));
  EXPECT_FALSE(fs::exists(still));
}

TEST(CliErrors, SimulationOptions) {
  const fs::path dir = ownDir(), d = dir / "no-dataset", rec = dir / "rec", frames = dir / "frames",
                 still = dir / "still.png";
  const std::string record = "record " + q(d) + " --path p.json --out " + q(rec);
  const std::string fly = "fly " + q(d) + " --headless --out " + q(frames);
  const std::string snapshot = "snapshot --lat 37.4 --lon -113 --alt 2 --heading 0 --pitch -10 --out " + q(still);
  for (const std::string& command : {record, fly, snapshot})
    expectOneLineUserErrors({{command + " --wind-speed 101", "--wind-speed 101: must be 0 … 100 m/s"},
                             {command + " --wind-speed -5", "--wind-speed -5"},
                             {command + " --gustiness -0.1", "--gustiness -0.1: must be 0 … 1"},
                             {command + " --gustiness 1.01", "--gustiness 1.01"},
                             {command + " --trail-budget-mb 0", "--trail-budget-mb 0: must be more than 0"},
                             {command + " --wind-direction nan", "--wind-direction nan: must be a finite number"}},
                            "--");
  // Not a number at all: CLI11 refuses it while parsing.
  expectOneLineUserErrors({{record + " --wind-speed fast", "--wind-speed"},
                           {record + " --trail-budget-mb", "--trail-budget-mb"}},
                          "vegstream record");
  EXPECT_FALSE(fs::exists(rec));
  EXPECT_FALSE(fs::exists(frames));
  EXPECT_FALSE(fs::exists(still));
}

// The sun options (app/sun_cli.h, issue 39) likewise: a malformed --datetime or --exposure is one
// line naming the option and the problem, exit 2, nothing written.
TEST(CliErrors, SunOptions) {
  const fs::path dir = ownDir(), d = dir / "no-dataset", rec = dir / "rec", frames = dir / "frames",
                 still = dir / "still.png";
  const std::string record = "record " + q(d) + " --path p.json --out " + q(rec);
  const std::string fly = "fly " + q(d) + " --headless --out " + q(frames);
  const std::string snapshot = "snapshot --lat 37.4 --lon -113 --alt 2 --heading 0 --pitch -10 --out " + q(still);
  for (const std::string& command : {record, fly, snapshot})
    expectOneLineUserErrors(
        {{command + " --datetime 2026-13-01", "--datetime \"2026-13-01\": month 13 does not exist"},
         {command + " --datetime 2026-06-21T06:45:00", "--datetime \"2026-06-21T06:45:00\": no zone"},
         {command + " --datetime 2026-02-30T06:45:00Z", "--datetime \"2026-02-30T06:45:00Z\": day 30 does not exist"},
         {command + " --datetime 2026-06-21T24:00:00Z", "hour 24 does not exist"},
         {command + " --datetime yesterday", "--datetime \"yesterday\": not an ISO 8601 date and time"},
         {command + " --datetime 2026-06-21T06:45:00Zulu", "after the zone"},
         {command + " --exposure nan", "--exposure nan: must be a number of EV from -10 to 30"},
         {command + " --exposure 31", "--exposure 31: must be"},
         {command + " --exposure -11", "--exposure -11: must be"},
         {command + " --exposure bright", "--exposure \"bright\": must be"},
         {command + " --datetime", "--datetime"}},
        "--");
  EXPECT_FALSE(fs::exists(rec));
  EXPECT_FALSE(fs::exists(frames));
  EXPECT_FALSE(fs::exists(still));
  for (const char* sub : {"fly", "record", "snapshot"}) {
    const auto r = runVegstream(std::string(sub) + " --help");
    EXPECT_NE(r.out.find("--datetime"), std::string::npos) << sub;
    EXPECT_NE(r.out.find("--exposure"), std::string::npos) << sub;
  }
}

TEST(CliErrors, Report) {
  const fs::path dir = ownDir(), rec = dir / "no-recording";
  expectOneLineUserErrors(
      {{"report", "dir"}, {"report " + q(rec) + " --bogus", "--bogus"}, {"report " + q(rec) + " extra", "extra"}},
      "vegstream report");
}

TEST(CliErrors, Compare) {
  const fs::path dir = ownDir(), a = dir / "a", b = dir / "b";
  const std::string ab = "compare " + q(a) + " " + q(b);
  expectOneLineUserErrors(
      {{"compare " + q(a), "dir_b"}, {ab + " --bogus", "--bogus"}, {ab + " --out", "--out"}, {ab + " extra", "extra"}},
      "vegstream compare");
}

TEST(CliErrors, Path) {
  const fs::path dir = ownDir(), d = dir / "no-dataset", out = dir / "p.json";
  const std::string ds = "path --dataset " + q(d);
  expectOneLineUserErrors({{"path --out " + q(out), "--dataset"},
                           {ds + " --out " + q(out) + " --bogus", "--bogus"},
                           {ds + " --out", "--out"},
                           {ds + " --out " + q(out) + " --template", "--template"},
                           {ds + " --out " + q(out) + " extra", "extra"}},
                          "vegstream path");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliErrors, Inspect) {
  ownDir();
  expectOneLineUserErrors({{"inspect blade-shape --stiffness 1 --bogus", "--bogus"},
                           {"inspect blade-shape --stiffness", "--stiffness"},
                           {"inspect blade-shape --stiffness 1 extra", "extra"}},
                          "vegstream inspect");
  // Values are checked after parsing (the option values are text until then): one line too.
  expectOneLineUserErrors({{"inspect blade-shape --stiffness 1 --segments 17", "--segments"},
                           {"inspect blade-shape --stiffness 1 --segments four", "--segments"},
                           {"inspect blade-shape --segments 4", "--stiffness"}},
                          "--");
}

TEST(CliErrors, Snapshot) {
  const fs::path dir = ownDir(), out = dir / "still.png";
  const std::string pose = "snapshot --lat 37.4 --lon -113 --alt 2 --heading 0 --pitch -10 --out " + q(out);
  expectOneLineUserErrors({{"snapshot --lon -113 --alt 2 --heading 0 --pitch -10 --out " + q(out), "--lat"},
                           {pose + " --bogus", "--bogus"},
                           {pose + " --alt-ref sky", "--alt-ref"},
                           {"snapshot --lat north --lon -113 --alt 2 --heading 0 --pitch -10 --out " + q(out), "--lat"},
                           {pose + " a b", "b"}},
                          "vegstream snapshot");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliErrors, Devices) {
  ownDir();
  expectOneLineUserErrors({{"devices --bogus", "--bogus"}, {"devices extra", "extra"}}, "vegstream devices");
}

TEST(CliErrors, NoOrUnknownSubcommand) {
  ownDir();
  expectOneLineUserErrors({{"", "subcommand"}, {"bogus", "bogus"}, {"--bogus", "--bogus"}}, "vegstream");
}

TEST(CliErrors, HelpIsPrintedAndExitsZero) {
  ownDir();
  for (const char* sub : {"", "import", "generate", "info", "query", "plants", "fly", "record", "report", "compare",
                          "path", "inspect", "snapshot", "devices"}) {
    SCOPED_TRACE(sub);
    const auto r = runVegstream(std::string(sub) + " --help");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << r.out;
    EXPECT_TRUE(r.err.empty()) << r.err;
  }
}

// The message says what failed: the Vulkan device, or the loader's call and its VkResult.
bool mentionsVulkan(const std::string& err) {
  return err.find("Vulkan") != std::string::npos || err.find("VK_ERROR_") != std::string::npos;
}

// No Vulkan driver loads (the loader is pointed at a driver list that does not exist): listing
// devices or opening one is the system's failure, not the user's — exit 1, one line.
TEST(CliErrors, NoVulkanDeviceIsExitOneWithOneLine) {
  const fs::path dir = ownDir();
  const std::string noDriver =
      "env -u VK_ADD_DRIVER_FILES VK_ICD_FILENAMES=/nonexistent.json "
      "VK_DRIVER_FILES=/nonexistent.json ";
  const auto devices = runCommand(noDriver + "'" + VEGSTREAM_EXE + "' devices");
  EXPECT_EQ(devices.exitCode, 1) << devices.err;
  EXPECT_EQ(countLines(devices.err), 1) << devices.err;
  EXPECT_TRUE(mentionsVulkan(devices.err)) << devices.err;
  EXPECT_TRUE(devices.out.empty()) << devices.out;

  // fly needs a dataset before it asks for a device: a small synthetic one.
  const fs::path dataset = dir / "synth";
  const auto g = runVegstream("generate --out " + q(dataset) + " --size-km 0.5 --max-zoom 12 --seed 3");
  ASSERT_EQ(g.exitCode, 0) << g.err;
  const fs::path out = dir / "frames";
  const auto fly = runCommand(noDriver + "'" + VEGSTREAM_EXE + "' fly " + q(dataset) +
                              " --headless --frames 1 --size 64x36 --out " + q(out));
  EXPECT_EQ(fly.exitCode, 1) << fly.err;
  EXPECT_EQ(countLines(fly.err), 1) << fly.err;
  EXPECT_TRUE(mentionsVulkan(fly.err)) << fly.err;
  EXPECT_FALSE(fs::exists(out / "run.json"));
}

// A catalog whose landcover table (vegetation/landcover_species.h, issue 41 item 2) names a
// species it does not have: one line naming the file and the field, exit 2, before any dataset
// is opened (the dataset below does not exist), for query and plants alike.
TEST(CliErrors, ALandcoverTableNamingAMissingSpeciesIsOneLine) {
  const fs::path dir = ownDir();
  const fs::path bad = dir / "landcover_species.json";
  {
    std::ofstream out(bad);
    out << R"({ "species": [ { "name": "grass", "reference": { "h_deg": 88, "s": 0.3, "v": 0.2 },
      "weights": { "h": 2, "s": 0.5, "v": 0.8 }, "p": 3, "kind": "grass",
      "height_m": { "min": 0.2, "max": 0.5 }, "stiffness": { "min": 1, "max": 1.5 },
      "width_m": { "min": 0.01, "max": 0.02 }, "colour_modulation": { "min": 0.9, "max": 1.1 } } ],
      "landcover": { "grass": ["grass"], "tree": ["oak"] } })";
  }
  for (const std::string& command :
       {"query " + q(dir / "no_dataset") + " --lat 37.4 --lon -113.0 --species " + q(bad),
        "plants " + q(dir / "no_dataset") + " --bbox -113.01,37.4,-113.0,37.41 --layer trees --species " + q(bad)}) {
    SCOPED_TRACE(command);
    const auto r = runVegstream(command);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("landcover_species.json"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("landcover.tree[0]"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("no species named \"oak\""), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

}  // namespace
}  // namespace vegstream::testing
