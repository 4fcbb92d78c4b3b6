// The shared simulation's step (simulation.h): clock, windows, colliders and sources for the GPU.

#include "simulation/simulation.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace vegstream::simulation {

namespace {

using shader::kFieldCellM;
using shader::kFieldTileTexels;
using shader::kFieldWindowTiles;
using shader::kRecoveryPerS;
using shader::kSubstepS;
using shader::kWindCellM;
using shader::kWindGrid;

int32_t floorDiv(double v, double cell) { return static_cast<int32_t>(std::floor(v / cell)); }

glm::vec4 towards(double degrees) {  // clockwise from north, as a unit ENU vector in zw
  const double r = degrees * std::numbers::pi / 180.0;
  return {0.0f, 0.0f, static_cast<float>(std::sin(r)), static_cast<float>(std::cos(r))};
}

InteractionWindowOptions windowOptions(const SimulationOptions& o) {
  InteractionWindowOptions w;
  w.windowTiles = kFieldWindowTiles;
  w.tileM = static_cast<double>(kFieldTileTexels) * static_cast<double>(kFieldCellM);
  w.recoveryPerS = static_cast<double>(kRecoveryPerS);
  w.tileBytes = static_cast<uint64_t>(kFieldTileTexels) * kFieldTileTexels * 16u;
  w.storeBytes = static_cast<uint64_t>(std::max(o.trailBudgetMb, 0.0) * 1024.0 * 1024.0);
  return w;
}

// The wind sources, world-anchored, into p (at most kMaxWindSources); returns how many.
std::size_t writeSources(std::span<const WindSourceState> in, shader::SimulationParams& p) {
  const auto sources = std::min<std::size_t>(in.size(), shader::kMaxWindSources);
  for (std::size_t i = 0; i < sources; ++i) {
    const WindSourceState& s = in[i];
    const glm::vec4 d = towards(s.directionDeg);
    p.sources[i].position = {static_cast<float>(s.position.x), static_cast<float>(s.position.y),
                             static_cast<float>(std::max(s.position.z - s.groundZ, 0.0)),
                             static_cast<float>(s.radiusM)};
    p.sources[i].params = {static_cast<float>(static_cast<int>(s.type)), static_cast<float>(s.strengthMps), d.z, d.w};
  }
  return sources;
}

}  // namespace

double colliderStrength(double radiusM) { return std::min(2.0 + 4.0 * radiusM, 10.0); }

Simulation::Simulation(const SimulationOptions& options)
    : options_(options), window_(std::make_unique<InteractionWindow>(windowOptions(options))) {}

void Simulation::restart(double timeS) {
  ++generation_;
  substepsDone_ = static_cast<int64_t>(std::floor(timeS * shader::kSubstepsPerS + 1e-6));
  window_ = std::make_unique<InteractionWindow>(windowOptions(options_));
  trailsUntilS_ = -1.0;
  previousColliders_.clear();
  started_ = true;
}

int64_t Simulation::advanceClock(double timeS, shader::SimulationParams& p) {
  // The clock: whole sub-steps from time 0, at most kMaxSubsteps a frame (the rest are dropped).
  // (Counted in whole sub-steps per second, not by dividing by the float kSubstepS: t = 1 s is 240.)
  const auto target = static_cast<int64_t>(std::floor(timeS * shader::kSubstepsPerS + 1e-6));
  const int64_t steps = std::clamp<int64_t>(target - substepsDone_, 0, shader::kMaxSubsteps);
  substepsDone_ = std::max(target, substepsDone_);
  const double stepS = 1.0 / shader::kSubstepsPerS;
  const double startS = static_cast<double>(substepsDone_ - steps) * stepS;
  p.clock = {static_cast<float>(steps), static_cast<float>(startS), kSubstepS,
             static_cast<float>(static_cast<double>(substepsDone_) * stepS)};
  return steps;
}

void Simulation::placeWindows(const glm::dvec3& cam, double timeS, int64_t steps, shader::SimulationParams& p) {
  const double stepS = 1.0 / shader::kSubstepsPerS;
  // Windows around the camera: integer cells and the camera's offset inside its cell.
  const glm::ivec2 windCell{floorDiv(cam.x, kWindCellM), floorDiv(cam.y, kWindCellM)};
  p.windCells = {windCell.x, windCell.y, windCell.x - kWindGrid / 2, windCell.y - kWindGrid / 2};
  p.windCamera = {static_cast<float>(cam.x - windCell.x * static_cast<double>(kWindCellM)),
                  static_cast<float>(cam.y - windCell.y * static_cast<double>(kWindCellM)), 0.0f, 0.0f};
  p.camera = {static_cast<float>(cam.x), static_cast<float>(cam.y), static_cast<float>(cam.z), 0.0f};
  gpu_.transfers = window_->update(cam.x, cam.y, timeS);
  const TileKey origin = window_->originTile();
  const glm::ivec2 texel{floorDiv(cam.x, kFieldCellM), floorDiv(cam.y, kFieldCellM)};
  p.fieldTexels = {texel.x, texel.y, origin.x, origin.y};
  const double recovery = static_cast<double>(kRecoveryPerS);
  p.field = {static_cast<float>(cam.x - texel.x * static_cast<double>(kFieldCellM)),
             static_cast<float>(cam.y - texel.y * static_cast<double>(kFieldCellM)),
             static_cast<float>(recovery * static_cast<double>(steps) * stepS), kRecoveryPerS};
  for (const TileTransfer& t : gpu_.transfers)
    if (t.kind == TileTransfer::Kind::Restore)
      p.restoredDecay[t.windowTile / 4][static_cast<int>(t.windowTile % 4)] = static_cast<float>(recovery * t.elapsedS);
}

std::size_t Simulation::writeColliders(const StepInput& in, shader::SimulationParams& p) {
  const glm::dvec3 cam = in.camera;
  const double recovery = static_cast<double>(kRecoveryPerS);
  // Colliders, camera-relative; swept from where they were one step ago (same index, same count).
  const auto colliders = std::min<std::size_t>(in.colliders.size(), shader::kMaxColliders);
  const bool sweep = previousColliders_.size() == colliders;
  for (std::size_t i = 0; i < colliders; ++i) {
    const ColliderState& c = in.colliders[i];
    const glm::dvec3 rel = c.centre - cam;
    const double half = 0.5 * c.lengthM;
    const double strength = colliderStrength(c.radiusM);
    p.colliders[i].centre = {static_cast<float>(rel.x), static_cast<float>(rel.y), static_cast<float>(rel.z),
                             static_cast<float>(c.radiusM)};
    p.colliders[i].shape = {static_cast<float>(half), static_cast<float>(c.groundZ - cam.z),
                            static_cast<float>(strength), sweep ? 1.0f : 0.0f};
    const glm::dvec3 prev = sweep ? previousColliders_[i] : c.centre;
    p.colliders[i].previous = {static_cast<float>(prev.x - cam.x), static_cast<float>(prev.y - cam.y),
                               static_cast<float>(prev.z - cam.z), 0.0f};
    // It marks the tiles it may press (its bottom within the grass layer) as holding a trail.
    if (c.centre.z - half - c.radiusM < c.groundZ + static_cast<double>(shader::kGrassReachM)) {
      window_->markHit(std::min(prev.x, c.centre.x) - c.radiusM, std::min(prev.y, c.centre.y) - c.radiusM,
                       std::max(prev.x, c.centre.x) + c.radiusM, std::max(prev.y, c.centre.y) + c.radiusM, in.timeS,
                       strength);
      trailsUntilS_ = std::max(trailsUntilS_, in.timeS + strength / recovery);
    }
  }
  previousColliders_.clear();
  for (std::size_t i = 0; i < colliders; ++i) previousColliders_.push_back(in.colliders[i].centre);
  return colliders;
}

void Simulation::step(const StepInput& in) {
  const bool restarting = !started_ || in.timeS < lastTimeS_;
  if (restarting) restart(in.timeS);
  lastTimeS_ = in.timeS;
  gpu_ = GpuStep{};
  gpu_.restarted = restarting;
  if (!options_.enabled) return;
  shader::SimulationParams& p = gpu_.params;

  const int64_t steps = advanceClock(in.timeS, p);
  // The mean wind blows from directionDeg, towards the opposite bearing.
  const glm::vec4 from = towards(options_.wind.directionDeg);
  const auto speed = static_cast<float>(options_.wind.speedMps);
  p.wind = {-from.z * speed, -from.w * speed, static_cast<float>(options_.wind.gustiness), 0.0f};

  placeWindows(in.camera, in.timeS, steps, p);
  const std::size_t sources = writeSources(in.sources, p);
  const std::size_t colliders = writeColliders(in, p);
  const bool wind = speed > 0.0f || sources > 0;
  const bool interaction = colliders > 0 || in.timeS <= trailsUntilS_;
  p.counts = {static_cast<int32_t>(sources), static_cast<int32_t>(colliders),
              (wind ? shader::kSimFlagWind : 0) | (interaction ? shader::kSimFlagInteraction : 0), generation_};
  gpu_.runWind = wind;
  gpu_.runInteraction = interaction;
}

}  // namespace vegstream::simulation
