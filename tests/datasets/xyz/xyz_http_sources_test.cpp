// The same tiles imported over HTTP from a real nginx on loopback (tests/support/nginx_server.h)
// give the same dataset as the directory import (xyz_fixture.h): URL templates with {y} and
// {-y} through the command line, where tiles over the bounds that the server does not have are
// 404s (no tile, not an error), and a PMTiles archive read by HTTP Range requests.

#include <chrono>
#include <set>
#include <thread>

#include <gtest/gtest.h>

#include "tests/datasets/xyz/xyz_fixture.h"
#include "tests/support/fault_http_server.h"
#include "tests/support/nginx_server.h"
#include "tests/support/pmtiles_writer.h"
#include "tests/support/run_command.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

class XyzOverHttp : public XyzSources {
 protected:
  void SetUp() override {
    XyzSources::SetUp();
    if (HasFatalFailure()) return;
    // The TMS copy of the imagery, and PMTiles archives, beside the site.
    for (const auto& [id, bytes] : sampleLayer("map"))
      writeBytes(site_ / "tms-imagery" / std::to_string(id.z) / std::to_string(id.x) /
                     (std::to_string((1 << id.z) - 1 - id.y) + ".png"),
                 bytes);
    writePmtiles(site_ / "elevation.pmtiles", sampleLayer("terrain-rgb"), {.gzipDirectories = true, .maxRootEntries = 2});
    writePmtiles(site_ / "imagery.pmtiles", sampleLayer("map"));
    auto server = NginxServer::start(site_, work_ / "nginx");
    ASSERT_TRUE(server.ok()) << server.error().message;
    nginx_ = std::move(*server);
  }
  // nginx writes a request's log line just after its answer: wait until `n` lines are there.
  std::vector<NginxLogLine> logOfAtLeast(size_t n) const {
    auto log = nginx_->accessLog();
    for (int i = 0; i < 100 && log.size() < n; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      log = nginx_->accessLog();
    }
    return log;
  }
  std::unique_ptr<NginxServer> nginx_;
};

TEST_F(XyzOverHttp, UrlTemplatesGiveTheSameTilesAndA404IsNoTile) {
  // Bounds reaching into the 4 × 4 tiles around the sample's 2 × 2: twelve of them are 404s.
  const auto nw = geo::tileBoundsLonLat({12, 757, 1607}), se = geo::tileBoundsLonLat({12, 760, 1610});
  const auto mid = [](double a, double b) { return 0.5 * (a + b); };
  char bounds[200];
  std::snprintf(bounds, sizeof bounds, "%.9f,%.9f,%.9f,%.9f", mid(nw.westDeg, nw.eastDeg),
                mid(se.southDeg, se.northDeg), mid(se.westDeg, se.eastDeg), mid(nw.southDeg, nw.northDeg));
  const fs::path out = work_ / "from-url";
  const auto r = runVegstream("import --xyz-elevation '" + nginx_->baseUrl() + "/elevation/{z}/{x}/{y}.png'" +
                              " --xyz-imagery '" + nginx_->baseUrl() + "/tms-imagery/{z}/{x}/{-y}.png'" +
                              " --encoding terrain-rgb --bounds " + bounds + " --max-zoom 12 --name grandcanyon" +
                              " --threads 2 --out '" + out.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectSameDataset(reference_, out);
  const auto log = logOfAtLeast(16 + 4);
  std::set<std::string> ok, missing;  // distinct tiles (the first one is also read by the size probe)
  for (const auto& l : log) {
    if (l.uri.rfind("/elevation/", 0) != 0) continue;
    EXPECT_TRUE(l.status == 200 || l.status == 404) << l.uri << " " << l.status;
    (l.status == 200 ? ok : missing).insert(l.uri);
  }
  EXPECT_EQ(ok.size(), 4u);
  EXPECT_EQ(missing.size(), 12u);
  EXPECT_TRUE(missing.contains("/elevation/12/757/1607.png"));
}

TEST_F(XyzOverHttp, PmtilesByRangeRequestsGiveTheSameTiles) {
  const fs::path out = work_ / "from-pmtiles-url";
  auto r = import(nginx_->baseUrl() + "/elevation.pmtiles", nginx_->baseUrl() + "/imagery.pmtiles", out);
  ASSERT_TRUE(r.ok()) << r.error().message;
  expectSameDataset(reference_, out);
  // Every answer was a 206 of a part of the archive, never the whole file.
  const uint64_t whole = fs::file_size(site_ / "elevation.pmtiles");
  const auto log = logOfAtLeast(2);
  size_t archiveRequests = 0;
  for (const auto& l : log) {
    if (l.uri != "/elevation.pmtiles") continue;
    ++archiveRequests;
    EXPECT_EQ(l.status, 206) << l.uri;
    EXPECT_LT(l.bytesSent, whole);
  }
  EXPECT_GE(archiveRequests, 1u + 4u);  // the first 16 KiB, then the leaves and tiles
}

// Reads over the network mostly wait: with threads 0, a URL import keeps remoteWorkers requests
// in flight even on a machine with fewer cores (every answer 200 ms late, 16 tiles).
TEST_F(XyzSources, UrlImportsKeepSeveralRequestsInFlight) {
  FaultHttpServer server(site_ / "elevation");
  server.setDefault({FaultAction::Serve, 200});
  auto o = options(server.baseUrl() + "/{z}/{x}/{y}.png", "", work_ / "concurrent");
  o.threads = 0;
  o.remoteWorkers = 8;
  o.maxZoom = 12;
  const auto nw = geo::tileBoundsLonLat({12, 757, 1607}), se = geo::tileBoundsLonLat({12, 760, 1610});
  o.bounds = geo::GeoBounds{nw.westDeg + 1e-6, se.southDeg + 1e-6, se.eastDeg - 1e-6, nw.northDeg - 1e-6};
  const auto start = std::chrono::steady_clock::now();
  auto r = datasets::importXyzTiles(o, makeNullLogger());
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(server.totalRequests(), 16u + 1u);  // the first tile asked for once more before the import
  EXPECT_GE(server.maxConcurrent(), 4) << "requests one after the other";
  EXPECT_LT(s, 16 * 0.2) << "16 answers of 200 ms each, not in parallel";
  // The same four tiles as from the directory.
  for (const auto& id : sampleTiles()) {
    const std::string rel = "elevation/12/" + std::to_string(id.x) + "/" + std::to_string(id.y) + ".png";
    EXPECT_EQ(bytesOf(work_ / "concurrent" / rel), bytesOf(reference_ / rel)) << rel;
  }
}

}  // namespace
}  // namespace vegstream::testing
