// `vegstream import --xyz-elevation` mistakes through the real command line: one line on stderr
// naming the URL or file and the problem, exit code 2, nothing at --out (DESIGN.md, "User
// mistakes"): a URL template without --bounds / --max-zoom, a server nobody answers on, a server
// that answers 500 (after the retries), corrupt MBTiles and PMTiles archives, a bad --bounds;
// and SIGINT during a slow URL import (exit 130, nothing left).

#include <chrono>
#include <csignal>
#include <thread>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "tests/datasets/xyz/xyz_fixture.h"
#include "tests/support/fault_http_server.h"
#include "tests/support/mbtiles_writer.h"
#include "tests/support/nginx_server.h"
#include "tests/support/pmtiles_writer.h"
#include "tests/support/run_command.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

// Runs the import, expects exit 2 with one line holding every `needles` item, and nothing at out.
void expectRefused(const std::string& sourceArgs, const std::vector<std::string>& needles) {
  const fs::path out = testOutputDir() / "out";
  const auto r = runVegstream("import " + sourceArgs + " --encoding terrain-rgb --out '" + out.string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(countLines(r.err), 1) << r.err;
  for (const auto& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << "no '" << n << "' in: " << r.err;
  EXPECT_FALSE(fs::exists(out));
  size_t left = 0;  // nor a temporary directory beside it
  for (const auto& e : fs::directory_iterator(out.parent_path())) left += e.path().filename().string().find("out") != std::string::npos;
  EXPECT_EQ(left, 0u);
}

TEST(XyzBadInput, UrlTemplateNeedsBoundsAndMaxZoom) {
  const std::string url = "http://127.0.0.1:9/{z}/{x}/{y}.png";
  expectRefused("--xyz-elevation '" + url + "' --max-zoom 12", {url, "--bounds"});
  expectRefused("--xyz-elevation '" + url + "' --bounds -112.4,36.0,-112.2,36.2", {url, "--max-zoom"});
  expectRefused("--xyz-elevation '" + url + "' --max-zoom 12 --bounds -112.4,36.2,-112.2", {"--bounds", "W,S,E,N"});
  expectRefused("--xyz-elevation '" + url + "' --max-zoom 12 --bounds -112.4,36.2,-112.2,36.0", {"--bounds", "S < N"});
  expectRefused("--xyz-elevation 'http://127.0.0.1:9/{z}/{x}/{s}.png' --max-zoom 12 --bounds -112.4,36.0,-112.2,36.2",
                {"{s}"});
}

TEST(XyzBadInput, UnreachableServerNamesTheUrl) {
  const int port = findFreeLoopbackPort();
  const std::string base = "http://127.0.0.1:" + std::to_string(port);
  expectRefused("--xyz-elevation '" + base + "/{z}/{x}/{y}.png' --max-zoom 12 --bounds -112.4,36.1,-112.39,36.11",
                {base + "/12/", "attempts"});
  expectRefused("--xyz-elevation '" + base + "/e.pmtiles'", {base + "/e.pmtiles", "attempts"});
}

TEST(XyzBadInput, ServerErrorAfterRetriesNamesTheUrlAndStatus) {
  const fs::path root = testOutputDir() / "root";
  for (const auto& [id, bytes] : sampleLayer("terrain-rgb"))
    writeBytes(root / std::to_string(id.z) / std::to_string(id.x) / (std::to_string(id.y) + ".png"), bytes);
  FaultHttpServer server(root);
  server.setDefault({FaultAction::Status500, 0});
  const auto b = geo::tileBoundsLonLat({12, 758, 1608});
  char bounds[160];
  std::snprintf(bounds, sizeof bounds, "%.9f,%.9f,%.9f,%.9f", b.westDeg + 0.01, b.southDeg + 0.01, b.eastDeg - 0.01,
                b.northDeg - 0.01);
  expectRefused("--xyz-elevation '" + server.baseUrl() + "/{z}/{x}/{y}.png' --max-zoom 12 --bounds " + bounds,
                {server.baseUrl() + "/12/758/1608.png", "HTTP 500", "4 attempts"});
  EXPECT_EQ(server.requestsFor("12/758/1608.png"), 4u);  // retried, then given up
}

TEST(XyzBadInput, CorruptMbtilesNamesTheFile) {
  const fs::path dir = testOutputDir() / "mb";
  fs::create_directories(dir);
  writeBytes(dir / "garbage.mbtiles", std::vector<uint8_t>(4096, 0x5a));
  expectRefused("--xyz-elevation '" + (dir / "garbage.mbtiles").string() + "'", {"garbage.mbtiles"});
  std::string error;
  ASSERT_TRUE(writeMbtiles(dir / "whole.mbtiles", sampleLayer("terrain-rgb"), "png", error)) << error;
  auto bytes = bytesOf(dir / "whole.mbtiles");
  bytes.resize(1024);  // the first page only: the tables' pages are gone
  writeBytes(dir / "cut.mbtiles", bytes);
  expectRefused("--xyz-elevation '" + (dir / "cut.mbtiles").string() + "'", {"cut.mbtiles"});
  expectRefused("--xyz-elevation '" + (dir / "missing.mbtiles").string() + "'", {"missing.mbtiles", "does not exist"});
}

TEST(XyzBadInput, CorruptPmtilesNamesTheFile) {
  const fs::path dir = testOutputDir() / "pm";
  const auto whole = buildPmtiles(sampleLayer("terrain-rgb"), {.gzipDirectories = true});
  writeBytes(dir / "short.pmtiles", std::vector<uint8_t>(whole.begin(), whole.begin() + 60));
  expectRefused("--xyz-elevation '" + (dir / "short.pmtiles").string() + "'", {"short.pmtiles", "truncated header"});
  auto magic = whole;
  magic[0] = 'X';
  writeBytes(dir / "magic.pmtiles", magic);
  expectRefused("--xyz-elevation '" + (dir / "magic.pmtiles").string() + "'", {"magic.pmtiles", "bad magic"});
  auto rootCut = whole;
  rootCut.resize(127 + 3);  // the header promises a root directory that is not there
  writeBytes(dir / "root.pmtiles", rootCut);
  expectRefused("--xyz-elevation '" + (dir / "root.pmtiles").string() + "'", {"root.pmtiles"});
  // A corrupt imagery archive is found before the elevation is imported: still one line.
  writeBytes(dir / "elevation.pmtiles", whole);
  expectRefused("--xyz-elevation '" + (dir / "elevation.pmtiles").string() + "' --xyz-imagery '" +
                    (dir / "magic.pmtiles").string() + "'",
                {"magic.pmtiles", "bad magic"});
  auto version = whole;
  version[7] = 2;
  writeBytes(dir / "v2.pmtiles", version);
  expectRefused("--xyz-elevation '" + (dir / "v2.pmtiles").string() + "'", {"v2.pmtiles", "version 2"});
}

// A slow server (every answer 150 ms late, 64 tiles, one thread): SIGINT a second in stops the
// import between tiles; exit 130 and nothing at --out.
TEST(XyzInterrupt, SigintDuringAUrlImportLeavesNothing) {
  const fs::path work = testOutputDir();
  for (const auto& [id, bytes] : sampleLayer("terrain-rgb"))
    writeBytes(work / "root" / std::to_string(id.z) / std::to_string(id.x) / (std::to_string(id.y) + ".png"), bytes);
  FaultHttpServer server(work / "root");
  server.setDefault({FaultAction::Serve, 150});
  const auto nw = geo::tileBoundsLonLat({12, 755, 1605}), se = geo::tileBoundsLonLat({12, 762, 1612});
  char bounds[160];
  std::snprintf(bounds, sizeof bounds, "%.9f,%.9f,%.9f,%.9f", nw.westDeg + 1e-6, se.southDeg + 1e-6, se.eastDeg - 1e-6,
                nw.northDeg - 1e-6);
  const fs::path out = work / "out";
  const std::string url = server.baseUrl() + "/{z}/{x}/{y}.png";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int devnull = ::open("/dev/null", O_WRONLY);
    ::dup2(devnull, 1), ::dup2(devnull, 2);
    ::execl(VEGSTREAM_EXE, VEGSTREAM_EXE, "import", "--xyz-elevation", url.c_str(), "--encoding", "terrain-rgb",
            "--bounds", bounds, "--max-zoom", "12", "--threads", "1", "--out", out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Wait until the import is under way (a few tiles asked for), then interrupt it.
  for (int i = 0; i < 200 && server.totalRequests() < 4; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(25));
  EXPECT_GE(server.totalRequests(), 4u);
  ::kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_LT(server.totalRequests(), 64u) << "stopped before the end";
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(work))
    EXPECT_EQ(e.path().filename().string().find("out"), std::string::npos) << e.path();
}

}  // namespace
}  // namespace vegstream::testing
