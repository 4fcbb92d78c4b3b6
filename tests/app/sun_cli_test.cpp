// The sun options of `fly`, `record` and `snapshot` (app/sun_cli.h): --datetime and --exposure
// are remembered as given, checked with one message naming the option, and --datetime wins over
// a flight path's "datetime". No GPU.

#include <algorithm>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include "app/sun_cli.h"
#include "flight/flight_path_json.h"

namespace vegstream::app {
namespace {

SunCli parsed(const std::vector<std::string>& args) {
  CLI::App app;
  SunCli cli;
  auto* cmd = app.add_subcommand("snapshot");
  addSunOptions(*cmd, cli);
  std::vector<std::string> argv = {"snapshot"};
  argv.insert(argv.end(), args.begin(), args.end());
  std::reverse(argv.begin(), argv.end());  // CLI11 takes the arguments reversed
  app.parse(argv);
  return cli;
}

std::string problem(const SunCli& cli) {
  const Result<SunSettings> r = checkSunOptions(cli);
  EXPECT_FALSE(r.ok());
  if (r.ok()) return "";
  EXPECT_EQ(r.error().kind, ErrorKind::InvalidInput);
  EXPECT_EQ(r.error().message.find('\n'), std::string::npos);
  return r.error().message;
}

TEST(SunCli, RemembersWhatWasGiven) {
  const SunCli none = parsed({});
  EXPECT_FALSE(none.datetime || none.exposure);
  const SunCli both = parsed({"--datetime", "2015-08-18T17:58:00Z", "--exposure", "-2.5"});
  EXPECT_EQ(both.datetime, "2015-08-18T17:58:00Z");
  EXPECT_EQ(both.exposure, "-2.5");
  const Result<SunSettings> s = checkSunOptions(both);
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_TRUE(s->datetime.has_value());
  EXPECT_EQ(s->datetime->unixMs, 1439920680000);
  EXPECT_EQ(s->exposureEv, -2.5f);
}

TEST(SunCli, NothingGivenLeavesTheSceneToChoose) {
  const Result<SunSettings> s = checkSunOptions({});
  ASSERT_TRUE(s.ok());
  scene::SceneOptions so;
  applySunOptions(*s, nullptr, so);
  EXPECT_FALSE(so.datetime.has_value());
  EXPECT_FALSE(so.exposureEv.has_value());
}

TEST(SunCli, BadValuesNameTheOption) {
  EXPECT_EQ(problem({std::string("2026-13-01"), std::nullopt}),
            "--datetime \"2026-13-01\": month 13 does not exist (01–12)");
  EXPECT_EQ(problem({std::string("2026-06-21T06:45:00"), std::nullopt}),
            "--datetime \"2026-06-21T06:45:00\": no zone: add Z for UTC or the offset it was written in, e.g. -06:00");
  EXPECT_EQ(problem({std::nullopt, std::string("nan")}), "--exposure nan: must be a number of EV from -10 to 30");
  EXPECT_EQ(problem({std::nullopt, std::string("inf")}), "--exposure inf: must be a number of EV from -10 to 30");
  EXPECT_EQ(problem({std::nullopt, std::string("31")}), "--exposure 31: must be a number of EV from -10 to 30");
  EXPECT_EQ(problem({std::nullopt, std::string("-10.5")}), "--exposure -10.5: must be a number of EV from -10 to 30");
  EXPECT_EQ(problem({std::nullopt, std::string("bright")}),
            "--exposure \"bright\": must be a number of EV from -10 to 30");
  EXPECT_EQ(problem({std::nullopt, std::string("3ev")}), "--exposure \"3ev\": must be a number of EV from -10 to 30");
  EXPECT_EQ(problem({std::nullopt, std::string("")}), "--exposure \"\": must be a number of EV from -10 to 30");
  EXPECT_TRUE(checkSunOptions({std::nullopt, std::string("-10")}).ok());
  EXPECT_TRUE(checkSunOptions({std::nullopt, std::string("30")}).ok());
}

TEST(SunCli, TheCommandLineWinsOverThePath) {
  auto path = flight::parseFlightPath(R"({"datetime": "2026-06-21T06:45:00-06:00",
    "keyframes": [{"t": 0, "lat": 37.2, "lon": -112.98, "alt_m": 500, "heading": 0, "pitch": -10},
                  {"t": 5, "lat": 37.21, "lon": -112.97, "alt_m": 500, "heading": 0, "pitch": -10}]})",
                                      "dawn.json");
  ASSERT_TRUE(path.ok()) << path.error().message;
  scene::SceneOptions so;
  applySunOptions(*checkSunOptions({}), &*path, so);
  EXPECT_EQ(so.datetime, path->datetime);
  const Result<SunSettings> given = checkSunOptions({std::string("2015-08-18T17:58:00Z"), std::string("12")});
  ASSERT_TRUE(given.ok());
  applySunOptions(*given, &*path, so);
  ASSERT_TRUE(so.datetime.has_value());
  EXPECT_EQ(so.datetime->unixMs, 1439920680000);
  EXPECT_EQ(so.exposureEv, 12.0f);
}

}  // namespace
}  // namespace vegstream::app
