// Streamed terrain (streamed_terrain.h): chunked-LOD selection → tile wants → pieces drawn from
// the nearest resident data, with geomorphing and imagery fade-in when finer data arrives.

#include "terrain/streamed_terrain.h"

#include <algorithm>
#include <cassert>
#include <set>

namespace vegstream::terrain {
namespace {

using streaming::TileKey;
using streaming::TileLayer;

geo::TileId ancestorAt(const geo::TileId& t, int z) {
  assert(z <= t.z && z >= 0);
  const int k = t.z - z;
  return {z, t.x >> k, t.y >> k};
}

constexpr double kRelaxStep = 1.5;      // per frame while the wants do not fit
constexpr double kRecoverStep = 1.05;   // per frame while they fit with room to spare
constexpr double kMaxRelaxation = 1024.0;
constexpr uint64_t kMeshIdleFrames = 240;
constexpr uint64_t kAheadEveryFrames = 4;
constexpr int kBeyondMaxZoom = kLevelsBeyondData;
static_assert((1 << kBeyondMaxZoom) * kNodeQuads == datasets::kTileSize);

}  // namespace

glm::vec4 ancestorUv(const geo::TileId& node, int levelsUp) {
  assert(levelsUp >= 0 && levelsUp <= node.z);
  const int n = 1 << levelsUp;
  const float scale = 1.0f / static_cast<float>(n);
  return {scale, scale, static_cast<float>(node.x & (n - 1)) * scale, static_cast<float>(node.y & (n - 1)) * scale};
}

StreamedTerrain::StreamedTerrain(streaming::TileStreamer& streamer, const geo::LocalFrame& frame,
                                 StreamedTerrainOptions options)
    : streamer_(&streamer), frame_(frame), options_(options) {
  const datasets::DatasetMeta& m = streamer.meta();
  dataset_.bounds = m.bounds;
  dataset_.minZoom = m.minZoom;
  // Nodes refine past the finest tiles until one mesh quad spans one height pixel
  // (2^kBeyondMaxZoom = tile pixels per quad), drawing sub-rectangles of the finest tiles.
  dataset_.maxZoom = m.maxZoom + kBeyondMaxZoom;
  tileMaxZoom_ = m.maxZoom;
  dataset_.minHeightM = m.minHeightM;
  dataset_.maxHeightM = m.maxHeightM;
}

void StreamedTerrain::relax() {
  // Feedback from the last update: the wanted tiles must fit both budgets at once, or the
  // streamer would evict and refetch them every frame (thrashing).
  const streaming::StreamingFrameStats& s = streamer_->frameStats();
  const bool hasImagery = streamer_->meta().imagery.has_value();
  const uint64_t imageryWanted = hasImagery ? s.wanted / 2 : 0;
  const bool tooMuch = s.wantsExceedCpuBudget || imageryWanted > streamer_->gpuSlotCount();
  const bool roomy = s.wantedBytes * 2 < streamer_->options().cpuBudgetBytes &&
                     imageryWanted * 2 < streamer_->gpuSlotCount();
  if (tooMuch) relaxation_ = std::min(kMaxRelaxation, relaxation_ * kRelaxStep);
  else if (roomy) relaxation_ = std::max(1.0, relaxation_ / kRecoverStep);
}

std::vector<streaming::TileWant> StreamedTerrain::wants(const SelectionView& now, std::span<const SelectionView> ahead) {
  ++frameNumber_;
  if (frameNumber_ > 1) relax();
  SelectionOptions so;
  so.maxErrorPx = options_.maxErrorPx * relaxation_;
  so.maxNodes = options_.maxNodes;
  selection_ = selectTiles(now, dataset_, frame_, so);
  // The look-ahead poses are seconds away: their selections change slowly, so they are redone
  // every kAheadEveryFrames frames (each costs as much as the frame's own selection).
  if (ahead.empty()) {
    aheadSelections_.clear();
  } else if (aheadSelections_.empty() || frameNumber_ % kAheadEveryFrames == 0) {
    aheadSelections_.clear();
    for (const SelectionView& view : ahead) aheadSelections_.push_back(selectTiles(view, dataset_, frame_, so));
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
  for (const auto& [id, priority] : wanted) add(tileFor(id), priority, false);
  for (const Selection& later : aheadSelections_) {
    for (const auto& [id, priority] : wantedTiles(later)) {
      const size_t before = out.size();
      add(tileFor(id), priority * options_.lookAheadPriority, true);
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

geo::TileId StreamedTerrain::tileFor(const geo::TileId& node) const {
  return node.z > tileMaxZoom_ ? ancestorAt(node, tileMaxZoom_) : node;
}

StreamedTerrain::NodeState StreamedTerrain::startState(const geo::TileId& node) const {
  // A node that appears by a split continues from what its nearest drawn ancestor showed.
  for (int z = node.z - 1; z >= dataset_.minZoom; --z) {
    auto it = nodes_.find(ancestorAt(node, z));
    if (it == nodes_.end() || it->second.lastFrame + 1 < frameNumber_) continue;
    NodeState s;
    s.heightZ = it->second.heightZ;
    s.imageryZ = it->second.imageryZ;
    s.layer = it->second.layer;
    if (s.imageryZ >= 0) s.uv = ancestorUv(node, node.z - s.imageryZ);
    return s;
  }
  return {};
}

const TerrainMesh& StreamedTerrain::meshFor(const geo::TileId& node, const streaming::ResidentTile& source,
                                            const streaming::ResidentTile* coarse) {
  const MeshKey key{node, source.key.id.z, coarse ? coarse->key.id.z : -1};
  auto it = meshes_.find(key);
  if (it == meshes_.end()) {
    NodeMeshOptions o;
    if (coarse) o.coarse = HeightSource{coarse->heights.get()};
    CachedMesh c{buildNodeMesh(node, HeightSource{source.heights.get()}, frame_, o), 0};
    it = meshes_.emplace(key, std::move(c)).first;
    ++figures_.meshesBuilt;
  }
  it->second.lastFrame = frameNumber_;
  return it->second.mesh.mesh;
}

std::span<const TerrainPiece> StreamedTerrain::pieces(double timeS) {
  pieces_.clear();
  const bool hasImagery = streamer_->meta().imagery.has_value();
  for (const SelectedNode& sn : selection_.nodes) {
    const geo::TileId& node = sn.id;
    const geo::TileId tile = tileFor(node);
    const int beyond = node.z - tile.z;  // levels past the finest tiles: never a fallback
    streaming::ResidentLookup height = streamer_->findResident({TileLayer::Height, tile});
    if (!height.tile || !height.tile->heights) continue;  // nothing resident under it yet (start-up)
    const int heightFallback = height.levelsUp - (tile.z - bestAvailable(TileLayer::Height, tile).z);
    height.levelsUp += beyond;
    auto [it, isNew] = nodes_.try_emplace(node);
    NodeState& st = it->second;
    if (isNew) st = startState(node);
    st.lastFrame = frameNumber_;

    // Heights: morph from the previous surface when the source gets finer.
    const int sourceZ = node.z - height.levelsUp;
    if (st.heightZ >= 0 && sourceZ > st.heightZ) {
      st.morphFromZ = st.heightZ;
      st.heightSwitchS = timeS;
    }
    st.heightZ = sourceZ;
    float morph = static_cast<float>(std::clamp(1.0 - (timeS - st.heightSwitchS) / options_.fadeS, 0.0, 1.0));
    std::shared_ptr<const streaming::ResidentTile> coarse;
    if (st.morphFromZ >= 0 && st.morphFromZ < sourceZ) {
      const MeshKey morphKey{node, sourceZ, st.morphFromZ};
      if (meshes_.count(morphKey) == 0 || morph > 0.0f)
        coarse = streamer_->get({TileLayer::Height, ancestorAt(node, st.morphFromZ)});
      if (!coarse && meshes_.count(morphKey) == 0) morph = 0.0f;
    }
    const bool useMorphMesh = st.morphFromZ >= 0 && st.morphFromZ < sourceZ &&
                              (coarse || meshes_.count({node, sourceZ, st.morphFromZ}) > 0);
    const TerrainMesh* mesh = nullptr;
    if (useMorphMesh) {
      auto cached = meshes_.find({node, sourceZ, st.morphFromZ});
      mesh = cached != meshes_.end() ? (cached->second.lastFrame = frameNumber_, &cached->second.mesh.mesh)
                                     : &meshFor(node, *height.tile, coarse.get());
    } else {
      mesh = &meshFor(node, *height.tile, nullptr);
      morph = 0.0f;
    }

    TerrainPiece p;
    p.mesh = mesh;
    p.node = node;
    p.heightLevelsUp = height.levelsUp;
    p.morph = morph;
    if (hasImagery) {
      streaming::TileStreamer::GpuLookup img = streamer_->findGpuResident({TileLayer::Imagery, tile});
      const int imageryBest = bestAvailable(TileLayer::Imagery, tile).z;
      const int imageryFallback = img.tile ? img.levelsUp - (tile.z - imageryBest) : imageryBest - dataset_.minZoom + 1;
      img.levelsUp += beyond;
      p.imageryFallback = imageryFallback;
      if (img.tile) {
        const int imageryZ = node.z - img.levelsUp;
        const auto layer = static_cast<int32_t>(img.slot);
        if (layer != st.layer || imageryZ != st.imageryZ) {
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
        } else {
          p.imageryBlend = 1.0f;
        }
      }
    }
    const int coarser = std::max(heightFallback, hasImagery ? p.imageryFallback : 0);
    if (coarser > 0) ++figures_.fallbackPieces;
    figures_.maxLevelsCoarser = std::max(figures_.maxLevelsCoarser, coarser);
    figures_.triangles += mesh->triangleCount();
    pieces_.push_back(p);
  }
  figures_.pieces = pieces_.size();

  // Forget what was not drawn for a while: node states after one frame (a split needs its
  // parent's state of the frame before), meshes after kMeshIdleFrames or beyond 4 × maxNodes.
  std::erase_if(nodes_, [&](const auto& kv) { return kv.second.lastFrame + 1 < frameNumber_; });
  std::erase_if(meshes_, [&](const auto& kv) { return kv.second.lastFrame + kMeshIdleFrames < frameNumber_; });
  const auto cap = static_cast<size_t>(4 * std::max(1, options_.maxNodes));
  while (meshes_.size() > cap) {
    auto oldest = std::min_element(meshes_.begin(), meshes_.end(),
                                   [](const auto& a, const auto& b) { return a.second.lastFrame < b.second.lastFrame; });
    if (oldest->second.lastFrame == frameNumber_) break;  // everything left is drawn this frame
    meshes_.erase(oldest);
  }
  return pieces_;
}

}  // namespace vegstream::terrain
