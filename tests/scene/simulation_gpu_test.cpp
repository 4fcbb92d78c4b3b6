// The shared simulation on the GPU (render/simulation_pass.h, lavapipe, validation on) against its
// CPU reference — the same shader text compiled as C++ (simulation/shared_code.h): the wind cells
// equal windAt within 1e-4 and the virtual blades' moments the CPU's integration; the field does
// not swim (two cameras, the same world cells, the same values) and is continuous across the
// toroidal wrap; a collider's press recovers on the GPU as the model says; a trail survives the
// camera leaving and coming back; the same windy flight gives the same images; the simulation's
// GPU memory does not grow with the plants drawn.

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "flight/path_sampler.h"
#include "scene/frame_driver.h"
#include "scene/playback.h"
#include "simulation/shared_code.h"
#include "tests/scene/scene_fixture.h"

namespace vegstream::scene {
namespace {
namespace fs = std::filesystem;
namespace sh = simulation::shader;

class SimulationGpuTest : public testing::SceneFrameTest {
 protected:
  // A pose near the ground of the benchmark path (its 15 m phase).
  FrameInput lowPose(const Scene& scene) {
    const flight::FlightPath p = path(scene);
    flight::PathSampler sampler(p);
    FrameInput in;
    in.pose = sampler.sample(12.0, scene.groundFunction());
    return in;
  }
  // Runs the simulation alone at 60 Hz from 0 to frames / 60 s.
  void advance(FrameDriver& driver, FrameInput in, int frames) {
    for (int k = 0; k <= frames; ++k) {
      in.timeS = k / 60.0;
      ASSERT_TRUE(driver.advanceSimulation(in).ok());
    }
  }
  static glm::dvec3 cameraOf(const Scene& scene, const FrameInput& in) { return scene.frame().toLocal(in.pose.position); }
};

simulation::SimulationOptions windy() {
  simulation::SimulationOptions o;
  o.wind = {.speedMps = 8.0, .directionDeg = 250.0, .gustiness = 0.7};
  return o;
}

// The world cell held at storage index i of a window whose first cell is `first`.
glm::ivec2 cellAt(int i, glm::ivec2 first) {
  const glm::ivec2 index(i % sh::kWindGrid, i / sh::kWindGrid);
  return first + ((index - first) & (sh::kWindGrid - 1));
}

TEST_F(SimulationGpuTest, WindCellsAndMomentsMatchTheCpuReference) {
  auto scene = open();
  ASSERT_TRUE(scene);
  FrameDriver driver(*scene, windy());
  FrameInput in = lowPose(*scene);
  flight::WindSourceSample whirl;
  whirl.type = flight::WindSourceSpec::Type::Whirlwind;
  whirl.centre = scene->frame().toGeodetic(cameraOf(*scene, in) + glm::dvec3(30.0, 0.0, 0.0));
  whirl.radiusM = 25.0;
  whirl.strengthMps = 12.0;
  in.windSources = {whirl};
  advance(driver, in, 30);  // 120 sub-steps
  auto read = scene->renderer().readSimulation();
  ASSERT_TRUE(read.ok()) << read.error().message;
  const sh::SimulationParams& p = driver.simulation().gpuStep().params;
  const glm::ivec2 first(p.windCells.z, p.windCells.w);
  double maxDiff = 0.0, maxSpeed = 0.0, maxMomentDiff = 0.0, maxMoment = 0.0;
  for (int i = 0; i < sh::kWindGrid * sh::kWindGrid; ++i) {
    const glm::ivec2 c = cellAt(i, first);
    const sh::vec2 centre = (sh::vec2(c) + 0.5f) * sh::kWindCellM;
    const sh::vec3 cpu = sh::windAt(p, centre, p.clock.w);
    const glm::vec4 gpu = read->windCells[static_cast<size_t>(i)].wind;
    maxDiff = std::max(maxDiff, static_cast<double>(glm::length(glm::vec3(gpu) - cpu)));
    maxSpeed = std::max(maxSpeed, static_cast<double>(glm::length(cpu)));
    if (i % 97 != 0) continue;  // the integration for a sample of 169 cells
    sh::VirtualBlade b = sh::virtualBladeAtRest(sh::windAt(p, centre, 0.0f));
    for (int k = 0; k < 120; ++k) sh::virtualBladeStep(b, sh::windAt(p, centre, static_cast<float>(k) * sh::kSubstepS), sh::kSubstepS);
    const sh::BladeMoments m = sh::virtualBladeMoments(b);
    const glm::vec4 g01 = read->windCells[static_cast<size_t>(i)].moments01;
    maxMomentDiff = std::max({maxMomentDiff, static_cast<double>(glm::length(glm::vec2(g01.x, g01.y) - m.m[0])),
                              static_cast<double>(glm::length(glm::vec2(g01.z, g01.w) - m.m[1]))});
    maxMoment = std::max(maxMoment, static_cast<double>(glm::length(m.m[0])));
  }
  EXPECT_LT(maxDiff, 1e-4);
  EXPECT_GT(maxSpeed, 10.0);   // the mean wind, gusts and the whirlwind: a real field
  EXPECT_GT(maxMoment, 0.01);  // the blades do lean
  EXPECT_LT(maxMomentDiff, 1e-3 * std::max(maxMoment, 1.0));
}

TEST_F(SimulationGpuTest, WindDoesNotSwimAndIsContinuousAcrossTheWrap) {
  auto scene = open();
  ASSERT_TRUE(scene);
  FrameInput a = lowPose(*scene);
  FrameInput b = a;  // 37 m east, 53 m south: a window over mostly the same world cells
  b.pose.position = scene->frame().toGeodetic(cameraOf(*scene, a) + glm::dvec3(37.0, -53.0, 0.0));
  render::Renderer::SimulationReadback reads[2];
  sh::SimulationParams params[2];
  for (int run = 0; run < 2; ++run) {
    FrameDriver driver(*scene, windy());  // a new driver: the GPU state starts over
    advance(driver, run == 0 ? a : b, 30);
    auto read = scene->renderer().readSimulation();
    ASSERT_TRUE(read.ok());
    reads[run] = std::move(*read);
    params[run] = driver.simulation().gpuStep().params;
  }
  const glm::ivec2 first0(params[0].windCells.z, params[0].windCells.w), first1(params[1].windCells.z, params[1].windCells.w);
  ASSERT_NE(first0, first1);
  int shared = 0;
  double maxDiff = 0.0;
  for (int i = 0; i < sh::kWindGrid * sh::kWindGrid; ++i) {
    const glm::ivec2 c = cellAt(i, first0);
    const glm::ivec2 off = c - first1;
    if (off.x < 0 || off.y < 0 || off.x >= sh::kWindGrid || off.y >= sh::kWindGrid) continue;
    ++shared;  // held at the same storage index in both (toroidal): compare wind and moments
    const sh::WindCellGpu& x = reads[0].windCells[static_cast<size_t>(i)];
    const sh::WindCellGpu& y = reads[1].windCells[static_cast<size_t>(i)];
    maxDiff = std::max({maxDiff, static_cast<double>(glm::length(x.wind - y.wind)),
                        static_cast<double>(glm::length(x.moments01 - y.moments01)),
                        static_cast<double>(glm::length(x.moments23 - y.moments23))});
  }
  EXPECT_GT(shared, 12000);
  EXPECT_LT(maxDiff, 1e-6);

  // Continuity: neighbours in the world that sit on either side of the storage seam (index 127
  // next to 0) differ no more than world neighbours anywhere in the window.
  const glm::ivec2 first = first1;
  ASSERT_NE(first.x & (sh::kWindGrid - 1), 0);  // the seam is inside the window, not at its edge
  double seam = 0.0, anywhere = 0.0;
  int seamPairs = 0;
  for (int y = 0; y < sh::kWindGrid; ++y)
    for (int x = 0; x + 1 < sh::kWindGrid; ++x) {
      const glm::ivec2 c = first + glm::ivec2(x, y), d = c + glm::ivec2(1, 0);
      const int i = (c.x & 127) + (c.y & 127) * 128, j = (d.x & 127) + (d.y & 127) * 128;
      const double diff = glm::length(reads[1].windCells[static_cast<size_t>(i)].moments01 -
                                      reads[1].windCells[static_cast<size_t>(j)].moments01);
      anywhere = std::max(anywhere, diff);
      if ((c.x & 127) == 127) {
        seam = std::max(seam, diff);
        ++seamPairs;
      }
    }
  EXPECT_EQ(seamPairs, sh::kWindGrid);
  EXPECT_GT(anywhere, 0.0);
  EXPECT_LE(seam, anywhere);
}

// A ball resting on the ground next to the camera for one frame, then gone: the texel under its
// centre holds cs0 = colliderStrength(0.5) and falls by c_r per second, to 2 %.
TEST_F(SimulationGpuTest, CollisionRecoversAsTheModelSays) {
  auto scene = open();
  ASSERT_TRUE(scene);
  FrameDriver driver(*scene, simulation::SimulationOptions{});
  FrameInput in = lowPose(*scene);
  const glm::dvec3 cam = cameraOf(*scene, in);
  const glm::dvec3 ballXY = cam + glm::dvec3(4.0, 3.0, 0.0);
  const geo::Geodetic g = scene->frame().toGeodetic(ballXY);
  const double ground = scene->groundHeight(g.latDeg, g.lonDeg);
  flight::ColliderSample ball;
  ball.centre = {g.latDeg, g.lonDeg, ground + 0.5};
  ball.radiusM = 0.5;
  in.colliders = {ball};
  in.timeS = 0.0;
  ASSERT_TRUE(driver.advanceSimulation(in).ok());
  in.timeS = 1.0 / 60.0;
  ASSERT_TRUE(driver.advanceSimulation(in).ok());
  in.colliders.clear();
  for (int k = 2; k <= 300; ++k) {
    in.timeS = k / 60.0;
    ASSERT_TRUE(driver.advanceSimulation(in).ok());
  }
  auto read = scene->renderer().readSimulation();
  ASSERT_TRUE(read.ok());
  const sh::SimulationParams& p = driver.simulation().gpuStep().params;
  const glm::dvec3 centre = scene->frame().toLocal(ball.centre);
  const int at = sh::fieldTexelIndex(p, sh::vec3(centre - cam));
  ASSERT_GE(at, 0);
  const double cs0 = simulation::colliderStrength(0.5);
  // Pressed in the first two frames (the second at 1/60 s), then 299 frames of recovery.
  const double expected = cs0 - static_cast<double>(sh::kRecoveryPerS) * (300 - 1) / 60.0;
  EXPECT_NEAR(read->field[static_cast<size_t>(at)].z, expected, 0.02 * expected);
  // 2 m away nothing was pressed.
  const int far = sh::fieldTexelIndex(p, sh::vec3(centre - cam + glm::dvec3(2.0, 0.0, 0.0)));
  ASSERT_GE(far, 0);
  EXPECT_EQ(read->field[static_cast<size_t>(far)].z, 0.0f);
}

// A trail pressed at t = 0; the camera flies 300 m away (the trail's tiles leave the window and
// go to the trail store) and comes back at t = 4 s: the trail is there with 4 s of recovery.
TEST_F(SimulationGpuTest, TrailSurvivesTheCameraLeavingAndReturning) {
  auto scene = open();
  ASSERT_TRUE(scene);
  FrameDriver driver(*scene, simulation::SimulationOptions{});
  FrameInput home = lowPose(*scene);
  const glm::dvec3 cam = cameraOf(*scene, home);
  const geo::Geodetic g = scene->frame().toGeodetic(cam + glm::dvec3(-5.0, 2.0, 0.0));
  flight::ColliderSample wheel;
  wheel.centre = {g.latDeg, g.lonDeg, scene->groundHeight(g.latDeg, g.lonDeg) + 0.4};
  wheel.radiusM = 0.6;
  FrameInput in = home;
  in.colliders = {wheel};
  in.timeS = 0.0;
  ASSERT_TRUE(driver.advanceSimulation(in).ok());
  FrameInput away = home;
  away.pose.position = scene->frame().toGeodetic(cam + glm::dvec3(300.0, 0.0, 0.0));
  for (int k = 1; k < 240; ++k) {
    away.timeS = k / 60.0;
    ASSERT_TRUE(driver.advanceSimulation(away).ok());
  }
  EXPECT_GT(driver.simulation().interactionWindow().storedTiles(), 0u);
  in = home;
  in.timeS = 4.0;
  ASSERT_TRUE(driver.advanceSimulation(in).ok());
  auto read = scene->renderer().readSimulation();
  ASSERT_TRUE(read.ok());
  const sh::SimulationParams& p = driver.simulation().gpuStep().params;
  const int at = sh::fieldTexelIndex(p, sh::vec3(scene->frame().toLocal(wheel.centre) - cam));
  ASSERT_GE(at, 0);
  const double cs0 = simulation::colliderStrength(0.6) * 1.0;  // pressed fully at its centre
  const double expected = cs0 - static_cast<double>(sh::kRecoveryPerS) * 4.0;
  EXPECT_NEAR(read->field[static_cast<size_t>(at)].z, expected, 0.02 * expected);
}

// Determinism with wind and a collider: two playbacks, the same counts and PNGs.
TEST_F(SimulationGpuTest, SameWindyFlightGivesTheSameImages) {
  std::vector<std::string> images[2];
  std::vector<double> plants[2];
  for (int run = 0; run < 2; ++run) {
    auto scene = open();
    ASSERT_TRUE(scene);
    flight::FlightPath p = path(*scene);
    flight::Collider ball;
    ball.name = "ball";
    ball.radiusM = 1.0;
    for (int k = 0; k < 2; ++k) {
      const flight::Keyframe& kf = p.keyframes[static_cast<size_t>(k)];
      ball.keyframes.push_back({k * 30.0, kf.lat, kf.lon, 1.0, flight::AltRef::Terrain});
    }
    p.colliders = {ball};
    FrameDriver driver(*scene, windy());
    PlaybackOptions po;
    po.fps = 1.0;
    po.framesEvery = 10;
    po.framesDir = dir / ("frames" + std::to_string(run));
    fs::create_directories(po.framesDir);
    auto rec = playFlight(driver, p, po);
    ASSERT_TRUE(rec.ok()) << rec.error().message;
    plants[run] = rec->table.values(*rec->table.find("plants"));
    for (const auto& e : fs::directory_iterator(po.framesDir)) {
      std::ifstream f(e.path(), std::ios::binary);
      images[run].push_back(e.path().filename().string() + std::string((std::istreambuf_iterator<char>(f)), {}));
    }
    std::sort(images[run].begin(), images[run].end());
  }
  EXPECT_EQ(plants[0], plants[1]);
  ASSERT_EQ(images[0].size(), 8u);  // four stills and their sidecars (issue 39), both byte for byte
  EXPECT_TRUE(images[0] == images[1]);
}

// No per-blade state: the simulation's GPU memory is the same however many plants are drawn.
TEST_F(SimulationGpuTest, GpuMemoryDoesNotGrowWithPlants) {
  auto scene = open();
  ASSERT_TRUE(scene);
  const uint64_t before = scene->renderer().simulationGpuBytes();
  FrameDriver driver(*scene, windy());
  FrameInput in = lowPose(*scene);
  uint64_t drawn = 0;
  for (int k = 0; k < 4; ++k) {
    in.timeS = k / 60.0;
    auto f = driver.run(in);
    ASSERT_TRUE(f.ok());
    if (f->vegetation && f->vegetation->gpuCounts) drawn = std::max(drawn, f->vegetation->plantsTotal);
  }
  EXPECT_GT(drawn, 1000u);
  EXPECT_EQ(scene->renderer().simulationGpuBytes(), before);
  // The whole of it: virtual blades, wind cells, field, the default 16 MiB store, three blocks.
  EXPECT_EQ(before, 128u * 128u * (80u + 48u) + 1024u * 1024u * 16u + (16u << 20) +
                        render::kFramesInFlight * sizeof(sh::SimulationParams));
}

}  // namespace
}  // namespace vegstream::scene

