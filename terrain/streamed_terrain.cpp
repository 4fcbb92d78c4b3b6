// Streamed terrain (streamed_terrain.h): chunked-LOD selection → tile wants; ROAM over the
// resident heights → pieces coloured from the nearest resident imagery, with imagery fade-in.

#include "terrain/streamed_terrain.h"

#include <algorithm>
#include <cassert>
#include <set>

#include "core/parallel_for.h"
#include "terrain/wedgie_table.h"

namespace vegstream::terrain {
namespace {

using streaming::TileKey;
using streaming::TileLayer;

geo::TileId ancestorAt(const geo::TileId& t, int z) {
  assert(z <= t.z && z >= 0);
  const int k = t.z - z;
  return {z, t.x >> k, t.y >> k};
}

constexpr double kRelaxStep = 1.5;     // per frame while the wants do not fit
constexpr double kRecoverStep = 1.05;  // per frame while they fit with room to spare
constexpr double kMaxRelaxation = 1024.0;
constexpr uint64_t kAheadEveryFrames = 4;

}  // namespace

glm::vec4 ancestorUv(const geo::TileId& node, int levelsUp) {
  assert(levelsUp >= 0 && levelsUp <= node.z);
  const int n = 1 << levelsUp;
  const float scale = 1.0f / static_cast<float>(n);
  return {scale, scale, static_cast<float>(node.x & (n - 1)) * scale, static_cast<float>(node.y & (n - 1)) * scale};
}

streaming::StreamingOptions streamingOptionsFor(const datasets::DatasetMeta& meta, streaming::StreamingOptions base) {
  base.heightExtra = wedgieTableBuilder(meta.minZoom);
  base.heightExtraBytes = wedgieTableBytes();
  return base;
}

StreamedTerrain::StreamedTerrain(streaming::TileStreamer& streamer, const geo::LocalFrame& frame,
                                 StreamedTerrainOptions options)
    : streamer_(&streamer), frame_(frame), options_(options) {
  const datasets::DatasetMeta& m = streamer.meta();
  dataset_.bounds = m.bounds;
  dataset_.minZoom = m.minZoom;
  dataset_.maxZoom = m.maxZoom;  // ROAM refines below a tile down to its pixels
  dataset_.minHeightM = m.minHeightM;
  dataset_.maxHeightM = m.maxHeightM;
  const BintreeGrid grid = gridForSeeds(m.minZoom, m.maxZoom, m.bounds.centre().y, options.seeds.targetAreaM2);
  heights_ = std::make_unique<ResidentHeights>(grid, findResidentHeights(streamer));
  const std::vector<geo::TileRange> ranges = geo::tileRangesCovering(m.bounds, m.minZoom);
  assert(ranges.size() == 1 && "datasets across the antimeridian are not supported by the bintree");
  RoamOptions ro = options.roam;
  ro.maxErrorPx = options.maxErrorPx;
  RoamMeshOptions mo;
  mo.fadeS = options.fadeS;
  mo.fillHeightM = 0.5 * (m.minHeightM + m.maxHeightM);
  roam_ = std::make_unique<RoamTessellator>(grid, ranges.front(), frame, *heights_, ro, options.seeds, mo,
                                            m.bounds.centre().y);
}

void StreamedTerrain::relax() {
  // Feedback from the last update: the wanted tiles must fit both budgets at once, or the
  // streamer would evict and refetch them every frame (thrashing).
  const streaming::StreamingFrameStats& s = streamer_->frameStats();
  const bool hasImagery = streamer_->meta().imagery.has_value();
  const uint64_t imageryWanted = hasImagery ? s.wanted / 2 : 0;
  const bool tooMuch = s.wantsExceedCpuBudget || imageryWanted > streamer_->gpuSlotCount();
  const bool roomy =
      s.wantedBytes * 2 < streamer_->options().cpuBudgetBytes && imageryWanted * 2 < streamer_->gpuSlotCount();
  if (tooMuch)
    relaxation_ = std::min(kMaxRelaxation, relaxation_ * kRelaxStep);
  else if (roomy)
    relaxation_ = std::max(1.0, relaxation_ / kRecoverStep);
}

std::vector<streaming::TileWant> StreamedTerrain::wants(const SelectionView& now, const EyeView& eye,
                                                        std::span<const SelectionView> ahead) {
  ++frameNumber_;
  eye_ = eye;
  if (frameNumber_ > 1) relax();
  SelectionOptions so;
  so.maxErrorPx = options_.maxErrorPx * relaxation_;
  so.maxNodes = options_.maxNodes;
  // The look-ahead poses are seconds away: their selections change slowly, so they are redone
  // every kAheadEveryFrames frames (each costs as much as the frame's own selection). The
  // selections are independent (plain data in, plain data out): with a task runner they are made
  // side by side, the frame thread taking its share, so a frame that redoes the look-ahead costs
  // about one selection instead of 1 + the poses. The same selections whatever ran where.
  const bool redoAhead = !ahead.empty() && (aheadSelections_.empty() || frameNumber_ % kAheadEveryFrames == 0);
  if (ahead.empty()) aheadSelections_.clear();
  if (redoAhead) aheadSelections_.assign(ahead.size(), Selection{});
  const size_t count = 1 + (redoAhead ? ahead.size() : 0);
  if (nodeBoxes_.size() < count) nodeBoxes_.resize(count);
  auto select = [&](size_t i) {
    if (i == 0)
      selection_ = selectTiles(now, dataset_, frame_, so, {}, &nodeBoxes_[0]);
    else
      aheadSelections_[i - 1] = selectTiles(ahead[i - 1], dataset_, frame_, so, {}, &nodeBoxes_[i]);
    return Status{};
  };
  if (options_.roam.tasks && count > 1) {
    const Status done = parallelFor(count, 0, options_.roam.tasks, select);
    assert(done.ok());
    (void)done;
  } else {
    for (size_t i = 0; i < count; ++i) (void)select(i);
  }
  figures_ = {};
  figures_.errorBoundPx = so.maxErrorPx;
  figures_.relaxation = relaxation_;
  figures_.achievedErrorPx = selection_.achievedErrorPx;
  figures_.budgetLimited = selection_.budgetLimited;
  return wantsAgain();
}

std::vector<streaming::TileWant> StreamedTerrain::wantsAgain() {
  figures_.lookAheadWants = 0;
  const bool hasImagery = streamer_->meta().imagery.has_value();
  std::vector<streaming::TileWant> out;
  std::set<TileKey> seen;
  auto add = [&](const geo::TileId& id, double priority, bool lookAhead) {
    for (TileLayer layer : {TileLayer::Height, TileLayer::Imagery}) {
      if (layer == TileLayer::Imagery && !hasImagery) continue;
      const TileKey key{layer, bestAvailable(layer, id)};
      if (seen.insert(key).second) out.push_back({key, priority, lookAhead});
    }
  };
  // The coarsest tiles under the view come first: they are what every fallback ends at.
  const auto wanted = wantedTiles(selection_);
  for (const auto& [id, priority] : wanted) add(ancestorAt(id, dataset_.minZoom), 1e9, false);
  for (const auto& [id, priority] : wanted) add(id, priority, false);
  for (const Selection& later : aheadSelections_) {
    for (const auto& [id, priority] : wantedTiles(later)) {
      const size_t before = out.size();
      add(id, priority * options_.lookAheadPriority, true);
      figures_.lookAheadWants += out.size() - before;
    }
  }
  return out;
}

geo::TileId StreamedTerrain::bestAvailable(streaming::TileLayer layer, const geo::TileId& tile) const {
  // A tile the dataset does not have (Failed: missing or corrupt) is a fact: its parent is the
  // best there is, so that is what is wanted and what a fallback is measured against.
  geo::TileId t = tile;
  while (t.z > dataset_.minZoom && streamer_->state({layer, t}) == streaming::TileState::Failed)
    t = ancestorAt(t, t.z - 1);
  return t;
}

StreamedTerrain::NodeState StreamedTerrain::startState(const geo::TileId& node) const {
  // A node that appears by a split continues from what its nearest drawn ancestor showed.
  for (int z = node.z - 1; z >= dataset_.minZoom; --z) {
    auto it = nodes_.find(ancestorAt(node, z));
    if (it == nodes_.end() || it->second.lastFrame + 1 < frameNumber_) continue;
    NodeState s;
    s.imageryZ = it->second.imageryZ;
    s.layer = it->second.layer;
    if (s.imageryZ >= 0) s.uv = ancestorUv(node, node.z - s.imageryZ);
    return s;
  }
  return {};
}

void StreamedTerrain::imageryFor(TerrainPiece& p, NodeState& st, double timeS) {
  const geo::TileId& node = p.node;
  streaming::TileStreamer::GpuLookup img = streamer_->findGpuResident({TileLayer::Imagery, node});
  const int imageryBest = bestAvailable(TileLayer::Imagery, node).z;
  p.imageryFallback = img.tile ? img.levelsUp - (node.z - imageryBest) : imageryBest - dataset_.minZoom + 1;
  if (!img.tile) return;
  const int imageryZ = node.z - img.levelsUp;
  const auto layer = static_cast<int32_t>(img.slot);
  if (layer != st.layer || imageryZ != st.imageryZ) {
    // Its first imagery (nothing drawn on it or its ancestors before): plants fade in. Not on
    // the first frame, whose imagery was there before anything was shown.
    if (st.layer < 0 && frameNumber_ > 1) st.arrivalS = timeS;
    // Fade from what was drawn, if that layer still holds the same tile.
    const bool finer = st.imageryZ >= 0 && imageryZ > st.imageryZ;
    bool previousValid = false;
    if (finer && st.layer >= 0) {
      const auto prev = streamer_->findGpuResident({TileLayer::Imagery, ancestorAt(node, st.imageryZ)});
      previousValid = prev.tile && prev.levelsUp == 0 && static_cast<int32_t>(prev.slot) == st.layer;
    }
    st.previousLayer = previousValid ? st.layer : -1;
    st.previousUv = previousValid ? ancestorUv(node, node.z - st.imageryZ) : glm::vec4(1, 1, 0, 0);
    st.imagerySwitchS = previousValid ? timeS : -1e9;
    st.layer = layer;
    st.imageryZ = imageryZ;
  }
  st.uv = ancestorUv(node, img.levelsUp);
  p.imageryLevelsUp = img.levelsUp;
  p.imageryLayer = layer;
  p.imageryUv = st.uv;
  p.imageryBlend = static_cast<float>(std::clamp((timeS - st.imagerySwitchS) / options_.fadeS, 0.0, 1.0));
  if (p.imageryBlend < 1.0f && st.previousLayer >= 0) {
    p.previousLayer = st.previousLayer;
    p.previousUv = st.previousUv;
    p.plantBlend = p.imageryBlend;
  } else {
    p.imageryBlend = 1.0f;
    p.plantBlend = static_cast<float>(std::clamp((timeS - st.arrivalS) / options_.fadeS, 0.0, 1.0));
  }
}

std::span<const TerrainPiece> StreamedTerrain::pieces(double timeS) {
  pieces_.clear();
  const bool hasImagery = streamer_->meta().imagery.has_value();
  // What arrived or left since the last frame: ROAM samples the ground under it again.
  heights_->newFrame();
  const std::vector<streaming::TileKey> changes = streamer_->takeResidencyChanges();
  roam_->tilesChanged(changes);

  std::vector<geo::TileId> tiles;
  tiles.reserve(selection_.nodes.size());
  for (const SelectedNode& sn : selection_.nodes) tiles.push_back(sn.id);
  pieceSet_.assign(tiles);
  roam_->update(eye_, pieceSet_, timeS);
  roam_->output(eye_, pieceSet_, timeS, meshes_, seeds_);

  std::vector<int32_t> drawnPiece(tiles.size(), -1);
  for (size_t i = 0; i < tiles.size(); ++i) {
    const geo::TileId& node = tiles[i];
    if (meshes_[i].empty()) continue;
    drawnPiece[i] = static_cast<int32_t>(pieces_.size());
    auto [it, isNew] = nodes_.try_emplace(node);
    NodeState& st = it->second;
    if (isNew) st = startState(node);
    st.lastFrame = frameNumber_;
    TerrainPiece p;
    p.mesh = &meshes_[i];
    p.node = node;
    const streaming::ResidentLookup height = streamer_->findResident({TileLayer::Height, node});
    p.heightLevelsUp = height.tile ? height.levelsUp : node.z - dataset_.minZoom + 1;
    const int heightFallback = p.heightLevelsUp - (node.z - bestAvailable(TileLayer::Height, node).z);
    if (hasImagery) imageryFor(p, st, timeS);
    const int coarser = std::max(heightFallback, hasImagery ? p.imageryFallback : 0);
    if (coarser > 0) ++figures_.fallbackPieces;
    figures_.maxLevelsCoarser = std::max(figures_.maxLevelsCoarser, coarser);
    pieces_.push_back(p);
  }
  seedImagery(tiles, drawnPiece);
  if (!meshes_.back().empty()) {  // leaves not yet inside one piece: coloured by height
    TerrainPiece p;
    p.mesh = &meshes_.back();
    pieces_.push_back(p);
  }
  const RoamFigures& rf = roam_->figures();
  figures_.roam = rf;
  figures_.seedLevel = roam_->seedLevel();
  figures_.pieces = pieces_.size();
  figures_.triangles = rf.drawnTriangles;
  figures_.meshesBuilt = pieces_.size();
  figures_.achievedErrorPx = rf.achievedErrorPx;
  figures_.budgetLimited = selection_.budgetLimited || rf.budgetLimited;

  // Forget node states not drawn last frame (a split needs its parent's state of the frame before).
  std::erase_if(nodes_, [&](const auto& kv) { return kv.second.lastFrame + 1 < frameNumber_; });
  return pieces_;
}

void StreamedTerrain::seedImagery(std::span<const geo::TileId> tiles, std::span<const int32_t> drawnPiece) {
  // Each seed triangle is coloured (and its species chosen) from the imagery its piece draws.
  const BintreeGrid& grid = roam_->grid();
  for (SeedTriangle& s : seeds_) {
    s.imageryLayer = -1;
    s.previousLayer = -1;
    s.imageryBlend = 1.0f;
    if (s.piece < 0 || static_cast<size_t>(s.piece) >= tiles.size()) continue;
    const int32_t drawn = drawnPiece[size_t(s.piece)];
    if (drawn < 0 || pieces_[size_t(drawn)].imageryLayer < 0) continue;
    const TerrainPiece& p = pieces_[size_t(drawn)];
    const geo::TileId& tile = tiles[size_t(s.piece)];
    const GridPoint corners[3] = {s.corners.apex, s.corners.left, s.corners.right};
    for (int k = 0; k < 3; ++k) {
      const glm::vec2 uv(grid.tileXY(corners[k], tile.z) - glm::dvec2(tile.x, tile.y));
      s.imageryUv[size_t(k)] = uv * glm::vec2(p.imageryUv.x, p.imageryUv.y) + glm::vec2(p.imageryUv.z, p.imageryUv.w);
      s.previousUv[size_t(k)] = uv * glm::vec2(p.previousUv.x, p.previousUv.y) + glm::vec2(p.previousUv.z, p.previousUv.w);
    }
    s.imageryLayer = p.imageryLayer;
    s.previousLayer = p.plantBlend < 1.0f ? p.previousLayer : -1;
    s.imageryBlend = p.plantBlend;
  }
}

}  // namespace vegstream::terrain
