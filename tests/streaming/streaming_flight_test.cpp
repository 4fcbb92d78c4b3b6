// Issue 5's flights: the Zion sample flown through scene::Scene with its tiles streamed —
// under a budget of a few MB, in realtime from a slow HTTP server with and without look-ahead
// (on a manual clock that the server's delays follow too), through a server that fails on a
// schedule (on the wall clock: libcurl's retries are what it tests), and settled over nginx
// against the local directory.
// Each test asserts numbers; the counts it measures are printed for the closing figures.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include <gtest/gtest.h>

#include "flight/flight_path_json.h"
#include "flight/path_sampler.h"
#include "scene/scene.h"
#include "streaming/http_tile_source.h"
#include "tests/streaming/streaming_fixture.h"
#include "tests/support/fault_http_server.h"
#include "tests/support/nginx_server.h"
#include "tests/support/run_command.h"

namespace vegstream::streaming::test {
namespace {

using Clock = std::chrono::steady_clock;

class StreamingFlight : public ZionDataset {
 protected:
  std::shared_ptr<render::ValidationLog> validation = std::make_shared<render::ValidationLog>();

  std::unique_ptr<scene::Scene> open(const std::string& location, scene::StreamingMode mode, bool lookAhead,
                                     uint64_t cpuBudget = 512ull << 20, uint64_t gpuBudget = 256ull << 20) {
    scene::SceneOptions o;
    o.dataset = location;
    o.mode = mode;
    o.lookAhead = lookAhead;
    o.streaming.cpuBudgetBytes = cpuBudget;
    o.streaming.gpuBudgetBytes = gpuBudget;
    o.renderer.width = 160;
    o.renderer.height = 90;
    o.renderer.msaa = 1;
    o.renderer.context.validate = true;
    o.renderer.context.validationLog = validation;
    auto scene = scene::Scene::open(o);
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : nullptr;
  }
  static constexpr double kSliceStartS = 160.0, kSliceS = 25.0;

  static flight::FlightPath bundled(const std::string& name) {
    auto p = flight::loadFlightPath(fs::path(VEGSTREAM_FLIGHT_PATHS_DIR) / (name + ".json"));
    EXPECT_TRUE(p.ok()) << p.error().message;
    return *p;
  }
  void TearDown() override {
    for (const auto& m : validation->messages()) ADD_FAILURE() << "validation: " << m;
  }

  // Realtime flight of [t0, t0 + seconds] of `path` at its recorded speed (flight time advances
  // with wall time), without rendering (streaming is what is measured). Counts the frames after
  // the first second that drew a tile more than one level coarser than wanted.
  struct RealtimeFigures {
    int frames = 0, coarseAfter1s = 0, fallbackFrames = 0;
    double slowestPrepareMs = 0.0;
  };
  RealtimeFigures flyRealtime(scene::Scene& scene, const flight::FlightPath& path, double seconds, double t0 = 0.0,
                              bool warmStart = false) {
    const flight::PathSampler sampler(path);
    const auto ground = scene.groundFunction();
    RealtimeFigures f;
    // A warm start loads the first pose's tiles first (realtime frames held at t0), so what is
    // measured is flying into new tiles, not the start-up.
    for (int i = 0; warmStart && i < 2000; ++i) {
      scene.prepareFrame(sampler.sample(t0, ground), t0, flight::lookAheadSamples(sampler, ground, t0));
      const scene::SceneFrameFigures& fig = scene.lastFrameFigures();
      if (fig.streaming.wanted == fig.streaming.wantedResident && fig.terrain.fallbackPieces == 0) break;
      scene.waitForTileArrivals(std::chrono::milliseconds(50));  // then the next frame takes it in
    }
    const auto start = Clock::now();
    for (;;) {
      const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
      if (elapsed > seconds) break;
      const double t = t0 + elapsed;
      const auto before = Clock::now();
      scene.prepareFrame(sampler.sample(t, ground), t, flight::lookAheadSamples(sampler, ground, t));
      f.slowestPrepareMs =
          std::max(f.slowestPrepareMs, std::chrono::duration<double, std::milli>(Clock::now() - before).count());
      const scene::SceneFrameFigures& fig = scene.lastFrameFigures();
      EXPECT_EQ(fig.settleWaitMs, 0.0);
      if (elapsed > 1.0 && fig.terrain.maxLevelsCoarser > 1) ++f.coarseAfter1s;
      if (fig.terrain.fallbackPieces > 0) ++f.fallbackFrames;
      ++f.frames;
      std::this_thread::sleep_until(before + std::chrono::milliseconds(16));  // about 60 frames per second
    }
    return f;
  }
};

// The realtime flight on a manual clock (issue 43): flight time and the server's delays both
// advance 1/30 s a frame, and before each frame the step's I/O settles (settleIo), so when a
// tile arrives depends on the flight and the server's delay, never on how fast this machine runs
// the frames or what else it runs: no sleeping, and the same frames every time.
class SteppedFlight : public StreamingFlight {
 protected:
  static constexpr double kStepS = 1.0 / 30.0;  // 30 frames a second of flight
  ManualClock clock;

  // After the clock moved: the server has begun every answer now due and sent each whole; each
  // transfer the HTTP source runs is one the server is still holding (every answered one was
  // handed on, and the requests it queued behind it have reached the server); nothing is being
  // decoded. False when that did not happen within 2 s.
  static bool settleIo(const scene::Scene& scene, testing::FaultHttpServer& server) {
    static const size_t kTransfers = static_cast<size_t>(streaming::HttpSourceOptions{}.maxInFlight);
    if (!server.settleClock(std::chrono::seconds(2))) return false;
    const auto limit = Clock::now() + std::chrono::seconds(2);
    for (;;) {
      const auto io = scene.tileIoProgress();
      const int held = server.activeRequests(), writing = server.answersBeingWritten();
      if (writing == 0 && static_cast<size_t>(held) == std::min(io.sourceInFlight, kTransfers) && io.decoding == 0)
        return true;
      if (Clock::now() > limit) {
        std::printf("unsettled: the server holds %d requests, writes %d answers; %zu in flight, %zu decoding\n", held,
                    writing, io.sourceInFlight, io.decoding);
        return false;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }

  // [t0, t0 + seconds] of `path`, a frame every kStepS of flight and server time, after a warm
  // start (frames held at t0, the clock still moving, until the first pose's tiles are in).
  RealtimeFigures fly(scene::Scene& scene, testing::FaultHttpServer& server, const flight::FlightPath& path,
                      double seconds, double t0) {
    const flight::PathSampler sampler(path);
    const auto ground = scene.groundFunction();
    RealtimeFigures f;
    int unsettled = 0;
    auto frame = [&](double t) {
      const auto before = Clock::now();
      scene.prepareFrame(sampler.sample(t, ground), t, flight::lookAheadSamples(sampler, ground, t));
      f.slowestPrepareMs =
          std::max(f.slowestPrepareMs, std::chrono::duration<double, std::milli>(Clock::now() - before).count());
      clock.advance(kStepS);
      unsettled += settleIo(scene, server) ? 0 : 1;
      return scene.lastFrameFigures();
    };
    for (int i = 0; i < 2000; ++i) {
      const scene::SceneFrameFigures fig = frame(t0);
      if (fig.streaming.wanted == fig.streaming.wantedResident && fig.terrain.fallbackPieces == 0) break;
    }
    const int steps = static_cast<int>(std::lround(seconds / kStepS));
    for (int i = 0; i <= steps; ++i) {
      const double elapsed = i * kStepS;
      const scene::SceneFrameFigures fig = frame(t0 + elapsed);
      EXPECT_EQ(fig.settleWaitMs, 0.0);
      if (elapsed > 1.0 && fig.terrain.maxLevelsCoarser > 1) ++f.coarseAfter1s;
      if (fig.terrain.fallbackPieces > 0) ++f.fallbackFrames;
      ++f.frames;
    }
    EXPECT_EQ(unsettled, 0) << "steps whose I/O did not settle within 2 s";
    return f;
  }

  // The scene over `server`, opened while the server answers at once (opening loads the ground
  // mosaic, blocking); then every answer is held `delayMs` of the manual clock.
  std::unique_ptr<scene::Scene> openDelayed(testing::FaultHttpServer& server, bool lookAhead, int delayMs) {
    server.setDefault({testing::FaultAction::Serve, 0});
    auto scene = open(server.baseUrl(), scene::StreamingMode::Realtime, lookAhead);
    server.setDefault({testing::FaultAction::Serve, delayMs});
    return scene;
  }
};

TEST_F(StreamingFlight, CanyonRunUnderAFewMegabytesKeepsResidentBytesWithinTheBudget) {
  constexpr uint64_t kCpuBudget = 6ull << 20, kGpuBudget = 3ull << 20;  // 24 decoded tiles, 12 imagery slots
  auto scene = open(dir().string(), scene::StreamingMode::Settled, true, kCpuBudget, kGpuBudget);
  ASSERT_TRUE(scene);
  const flight::FlightPath path = bundled("canyon-run");
  const flight::PathSampler sampler(path);
  const auto ground = scene->groundFunction();
  int frames = 0, relaxed = 0;
  uint64_t maxCpu = 0, maxGpu = 0, issued = 0, evicted = 0;
  double maxRelaxation = 1.0;
  for (double t = 0.0; t <= sampler.duration(); t += 0.5, ++frames) {
    render::FrameRequest req =
        scene->prepareFrame(sampler.sample(t, ground), t, flight::lookAheadSamples(sampler, ground, t));
    const scene::SceneFrameFigures& fig = scene->lastFrameFigures();
    ASSERT_LE(fig.streaming.bytesResidentCpu, kCpuBudget) << "t = " << t;
    ASSERT_LE(fig.streaming.bytesResidentGpu, kGpuBudget) << "t = " << t;
    ASSERT_GT(fig.terrain.pieces, 0u) << "t = " << t;
    maxCpu = std::max(maxCpu, fig.streaming.bytesResidentCpu);
    maxGpu = std::max(maxGpu, fig.streaming.bytesResidentGpu);
    relaxed += fig.terrain.relaxation > 1.0 ? 1 : 0;
    maxRelaxation = std::max(maxRelaxation, fig.terrain.relaxation);
    issued += fig.streaming.requestsIssued;
    evicted += fig.streaming.evictionsCpu;
    if (frames % 50 == 0) {  // the uploads and draws of a tight budget are valid Vulkan
      auto frame = scene->renderer().renderFrame(req);
      ASSERT_TRUE(frame.ok()) << frame.error().message;
    }
  }
  std::printf(
      "canyon-run, budget 6 MiB CPU / 3 MiB GPU: %d frames, max resident %.2f MiB CPU, %.2f MiB GPU, "
      "%d frames with a relaxed error bound (at most x%.1f), %llu requests, %llu evictions\n",
      frames, double(maxCpu) / (1 << 20), double(maxGpu) / (1 << 20), relaxed, maxRelaxation,
      static_cast<unsigned long long>(issued), static_cast<unsigned long long>(evicted));
  // No thrashing: the relaxed bound wants what fits, so tiles are not fetched and evicted over
  // and over — fewer requests than frames over the whole flight.
  EXPECT_LT(issued, static_cast<uint64_t>(frames));
  EXPECT_EQ(frames, 603);
  EXPECT_GT(relaxed, 0) << "a 6 MiB budget cannot hold what a 2 px bound wants: the bound must relax";
  EXPECT_GT(maxCpu, kCpuBudget / 2) << "the budget is used, not avoided";
}

TEST_F(SteppedFlight, LookAheadKeepsARealtimeFlightFromASlowServerWithinOneLevel) {
  // Zoom-14 tiles (about 2 km at Zion): the low, fast part of canyon-run (180 m/s at 90 m) crosses
  // one every ten seconds or so. 120 ms per tile, answered concurrently: a distant server.
  const fs::path fine = testTmp("flight-zion-z14");
  auto meta = importZion(fine, 14);
  ASSERT_TRUE(meta.ok()) << meta.error().message;
  testing::FaultHttpServer server(fine, &clock);
  const flight::FlightPath path = bundled("canyon-run");
  RealtimeFigures with, without;
  {
    auto scene = openDelayed(server, true, 120);
    ASSERT_TRUE(scene);
    with = fly(*scene, server, path, kSliceS, kSliceStartS);
  }
  {
    auto scene = openDelayed(server, false, 120);
    ASSERT_TRUE(scene);
    without = fly(*scene, server, path, kSliceS, kSliceStartS);
  }
  fs::remove_all(fine);
  std::printf(
      "canyon-run 160-185 s, 30 frames a second of a manual clock (warm start) over a 120 ms server: look-ahead "
      "on: %d frames, %d more than one level coarser after 1 s, %d with a fallback; off: %d frames, %d, %d\n",
      with.frames, with.coarseAfter1s, with.fallbackFrames, without.frames, without.coarseAfter1s,
      without.fallbackFrames);
  EXPECT_EQ(with.frames, 751);
  EXPECT_EQ(with.coarseAfter1s, 0);
  EXPECT_GT(without.coarseAfter1s + without.fallbackFrames, with.coarseAfter1s + with.fallbackFrames)
      << "without look-ahead, arriving tiles must show as fallbacks";
  EXPECT_LT(with.slowestPrepareMs, 1000.0) << "a realtime frame never waits for I/O";
}

TEST_F(StreamingFlight, ARealtimeFlightThroughAFailingServerCompletesWithEveryFailureAccounted) {
  testing::FaultHttpServer server(dir());
  server.setDefault({testing::FaultAction::Serve, 30});
  // Every 5th request fails in one of four ways; libcurl's retries and the streamer's back-off
  // must carry the flight through.
  for (uint64_t n = 3; n < 400; n += 5) {
    static const testing::FaultAction kinds[] = {testing::FaultAction::Status500, testing::FaultAction::Truncate,
                                                 testing::FaultAction::Reset, testing::FaultAction::Status503};
    server.scheduleForRequest(n, {kinds[(n / 5) % 4], 0});
  }
  auto scene = open(server.baseUrl(), scene::StreamingMode::Realtime, true);
  ASSERT_TRUE(scene);
  const RealtimeFigures f = flyRealtime(*scene, bundled("benchmark-30s"), 8.0);
  const scene::SceneFrameFigures& last = scene->lastFrameFigures();
  std::printf("benchmark-30s 0-8 s through faults: %d frames, slowest prepare %.1f ms, %llu server requests\n",
              f.frames, f.slowestPrepareMs, static_cast<unsigned long long>(server.totalRequests()));
  EXPECT_GT(f.frames, 100);
  EXPECT_LT(f.slowestPrepareMs, 1000.0);
  EXPECT_GT(server.totalRequests(), 20u);
  EXPECT_GT(last.streaming.tilesResidentCpu, 0u);
  EXPECT_EQ(last.streaming.wantedResident, last.streaming.wanted) << "every wanted tile arrives in the end";
}

TEST_F(StreamingFlight, ASettledFlightOverNginxDrawsWhatTheLocalDirectoryDraws) {
  auto nginx = testing::NginxServer::start(dir(), testTmp("nginx"));
  ASSERT_TRUE(nginx.ok()) << nginx.error().message;
  auto local = open(dir().string(), scene::StreamingMode::Settled, true);
  auto remote = open((*nginx)->baseUrl(), scene::StreamingMode::Settled, true);
  ASSERT_TRUE(local && remote);
  const flight::FlightPath path = bundled("benchmark-30s");
  const flight::PathSampler sampler(path);
  const auto ground = local->groundFunction();
  int compared = 0;
  for (double t = 0.0; t <= sampler.duration(); t += 2.5) {
    const flight::FlightSample s = sampler.sample(t, ground);
    const auto ahead = flight::lookAheadSamples(sampler, ground, t);
    render::FrameRequest a = local->prepareFrame(s, t, ahead);
    render::FrameRequest b = remote->prepareFrame(s, t, ahead);
    EXPECT_EQ(local->lastFrameFigures().terrain.pieces, remote->lastFrameFigures().terrain.pieces) << t;
    EXPECT_EQ(local->lastFrameFigures().terrain.triangles, remote->lastFrameFigures().terrain.triangles) << t;
    EXPECT_EQ(remote->lastFrameFigures().terrain.fallbackPieces, 0u) << t;
    a.readbackColor = b.readbackColor = true;
    auto fa = local->renderer().renderFrame(a);
    auto fb = remote->renderer().renderFrame(b);
    ASSERT_TRUE(fa.ok() && fb.ok());
    EXPECT_EQ(fa->terrainTriangles, fb->terrainTriangles) << t;
    EXPECT_TRUE(fa->color->rgba == fb->color->rgba) << "images differ at t = " << t;
    ++compared;
  }
  EXPECT_EQ(compared, 13);
  EXPECT_GT((*nginx)->accessLog().size(), 20u) << "the remote scene really read over HTTP";
}

// The user's side: `vegstream fly URL` flies over a dataset served by nginx; a URL with no
// dataset behind it is one message naming it, exit code 2, nothing written.
TEST_F(StreamingFlight, FlyOverAUrlWritesFramesAndAWrongUrlIsOneMessage) {
  auto nginx = testing::NginxServer::start(dir(), testTmp("nginx-cli"));
  ASSERT_TRUE(nginx.ok()) << nginx.error().message;
  const fs::path out = testTmp("fly-url");
  const auto ok =
      testing::runCommand(std::string(VEGSTREAM_EXE) + " fly " + (*nginx)->baseUrl() +
                          " --headless --validate --frames 2 --size 160x90 --msaa 1 --out '" + out.string() + "'");
  ASSERT_EQ(ok.exitCode, 0) << ok.err;
  EXPECT_TRUE(fs::exists(out / "frames" / "frame_00001.png"));
  EXPECT_NE(ok.err.find((*nginx)->baseUrl()), std::string::npos) << "the source is named";
  EXPECT_EQ(ok.err.find("validation:"), std::string::npos) << ok.err;

  const fs::path out2 = testTmp("fly-url-wrong");
  const std::string wrong = (*nginx)->baseUrl() + "/no-such-dataset";
  const auto bad = testing::runCommand(std::string(VEGSTREAM_EXE) + " fly " + wrong + " --headless --frames 2 --out '" +
                                       out2.string() + "'");
  EXPECT_EQ(bad.exitCode, 2) << bad.err;
  EXPECT_NE(bad.err.find(wrong), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(out2 / "run.json"));
}

}  // namespace
}  // namespace vegstream::streaming::test
