// The trees around the camera (tree_field.h): tiles placed once, pages nearest first.
#include "scene/tree_field.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/common.hpp>
#include <glm/gtc/color_space.hpp>
#include <glm/packing.hpp>

#include "core/hash.h"
#include "core/stopwatch.h"

namespace vegstream::scene {
namespace {

// The imagery's colour under a tree with a little of the tree's own (issue 41 item 5): ±8 %
// brightness and ±6 % between red and blue, from a hash of its seed, so neighbours of one species
// differ as real crowns do; zero-mean, so a stand keeps the imagery's colour from afar.
glm::vec3 ownTint(const vegetation::PlacedTree& t) {
  const uint32_t h = mix32(t.seed ^ 0x7a11c0deu);
  const float bright = 1.0f + 0.16f * (float(h & 0xffffu) / 65535.0f - 0.5f);
  const float warm = 0.12f * (float(h >> 16) / 65535.0f - 0.5f);
  return t.groundLinear * bright * glm::vec3(1.0f + warm, 1.0f, 1.0f - warm);
}

}  // namespace

TreeField::TreeField(const vegetation::SpeciesCatalog& catalog, vegetation::TreeGroundAt ground,
                     const TreeFieldOptions& options, std::vector<uint32_t> firstModel, uint32_t variants,
                     uint32_t pageCapacity)
    : catalog_(&catalog),
      ground_(std::move(ground)),
      options_(options),
      grid_(vegetation::treeGridFor(catalog)),
      firstModel_(std::move(firstModel)),
      variants_(std::max(variants, 1u)),
      pageCounts_(pageCapacity, 0u) {
  assert(options.tileCells > 0);
  // Pages are handed out lowest first, so the pool's used part stays compact.
  for (uint32_t p = pageCapacity; p-- > 0;) freePages_.push_back(p);
}

void TreeField::place(const TileKey& key, Tile& tile) {
  const auto n = static_cast<int32_t>(options_.tileCells);
  scratch_.clear();
  placeTreesWithCanopy(canopy_.get(), *catalog_, grid_, key.first * n, key.second * n, (key.first + 1) * n,
                       (key.second + 1) * n, ground_, scratch_);
  tile.trees.clear();
  tile.trees.reserve(scratch_.size());
  for (const vegetation::PlacedTree& t : scratch_) {
    if (t.species >= firstModel_.size() || firstModel_[t.species] == UINT32_MAX) continue;  // no model
    render::TreeInstanceGpu g{};
    g.position[0] = static_cast<float>(t.x);
    g.position[1] = static_cast<float>(t.y);
    g.position[2] = static_cast<float>(t.z);
    g.model = firstModel_[t.species] + t.seed % variants_;
    g.heightM = t.heightM;
    g.crownM = t.crownM;
    g.seed = t.seed;
    // The imagery under it, and a paler tree at the border of its colour.
    g.colour = glm::packUnorm4x8(glm::vec4(glm::convertLinearToSRGB(glm::clamp(ownTint(t), 0.0f, 1.0f)),
                                           0.8f + 0.2f * t.sPrime));
    tile.trees.push_back(g);
  }
  tile.placed = true;
}

void TreeField::freePages(Tile& tile) {
  for (uint32_t p : tile.pages) {
    pageCounts_[p] = 0;
    freePages_.push_back(p);
  }
  tile.pages.clear();
  std::sort(freePages_.begin(), freePages_.end(), std::greater<>());  // lowest at the back
}

TreeField::Wanted TreeField::wantedTiles(const glm::dvec3& camera) const {
  const double horizon = options_.lod.horizonM;
  const double side = grid_.cellM * options_.tileCells;
  // The tiles any part of which lies within the horizon, nearest first (ties by key: deterministic).
  Wanted wanted;
  const auto lo = [&](double c) { return static_cast<int32_t>(std::floor((c - horizon) / side)); };
  const auto hi = [&](double c) { return static_cast<int32_t>(std::floor((c + horizon) / side)); };
  for (int32_t ty = lo(camera.y); ty <= hi(camera.y); ++ty)
    for (int32_t tx = lo(camera.x); tx <= hi(camera.x); ++tx) {
      const double dx = std::max({tx * side - camera.x, 0.0, camera.x - (tx + 1) * side});
      const double dy = std::max({ty * side - camera.y, 0.0, camera.y - (ty + 1) * side});
      const double d = std::hypot(dx, dy);
      if (d < horizon) wanted.push_back({d, {tx, ty}});
    }
  std::sort(wanted.begin(), wanted.end());
  return wanted;
}

void TreeField::placeWanted(const Wanted& wanted, bool settled) {
  // Tiles that left the horizon go, with their pages.
  std::map<TileKey, Tile> kept;
  for (const auto& [d, key] : wanted) {
    auto it = tiles_.find(key);
    if (it != tiles_.end()) kept.emplace(key, std::move(it->second)), tiles_.erase(it);
  }
  for (auto& [key, tile] : tiles_) freePages(tile);
  tiles_ = std::move(kept);

  Stopwatch placing;
  for (const auto& [d, key] : wanted) {
    Tile& tile = tiles_[key];
    if (tile.placed) continue;
    if (!settled && figures_.placed >= options_.placementsPerFrame) continue;
    place(key, tile);
    ++figures_.placed;
  }
  figures_.placementMs = placing.elapsedMs();
}

// Pages, nearest first; a nearer tile takes the pages of the farthest that has some. Once one
// tile finds none, no farther tile is drawn either (the drawn trees are always the nearest).
void TreeField::assignPages(const Wanted& wanted) {
  bool bound = false;
  for (size_t i = 0; i < wanted.size(); ++i) {
    Tile& tile = tiles_[wanted[i].second];
    if (bound) {
      freePages(tile);
      continue;
    }
    if (!tile.placed || tile.trees.empty() || !tile.pages.empty()) continue;
    const auto need = static_cast<uint32_t>((tile.trees.size() + render::kTreePageSize - 1) / render::kTreePageSize);
    for (size_t j = wanted.size(); j-- > i + 1 && freePages_.size() < need;) {
      Tile& far = tiles_[wanted[j].second];
      if (!far.pages.empty()) freePages(far);
    }
    if (freePages_.size() < need) {
      figures_.budgetBound = bound = true;
      continue;
    }
    for (uint32_t k = 0; k < need; ++k) {
      const uint32_t page = freePages_.back();
      freePages_.pop_back();
      const size_t first = size_t{k} * render::kTreePageSize;
      const auto count = static_cast<uint32_t>(std::min<size_t>(render::kTreePageSize, tile.trees.size() - first));
      pageCounts_[page] = count;
      tile.pages.push_back(page);
      uploads_.push_back({page, count, tile.trees.data() + first});
    }
  }
}

uint32_t TreeField::countDrawn() {
  uint32_t highest = 0;
  for (const auto& [key, tile] : tiles_) {
    if (tile.placed && !tile.trees.empty() && tile.pages.empty()) figures_.budgetBound = true;
    if (tile.pages.empty()) continue;
    ++figures_.tilesDrawn;
    figures_.treesDrawn += tile.trees.size();
    figures_.pagesUsed += static_cast<uint32_t>(tile.pages.size());
    for (uint32_t p : tile.pages) highest = std::max(highest, p + 1);
  }
  return highest;
}

const render::TreeRequest& TreeField::prepare(const glm::dvec3& camera, bool settled) {
  figures_ = {};
  figures_.pageCapacity = static_cast<uint32_t>(pageCounts_.size());
  uploads_.clear();
  const Wanted wanted = wantedTiles(camera);
  figures_.tilesWanted = static_cast<uint32_t>(wanted.size());
  placeWanted(wanted, settled);
  assignPages(wanted);
  const uint32_t highest = countDrawn();
  request_.uploads = uploads_;
  request_.pageCounts = std::span<const uint32_t>(pageCounts_.data(), highest);
  request_.lod = options_.lod;
  request_.fades = options_.fades;
  request_.shadows = options_.shadows;
  request_.cores = options_.cores;
  request_.cameraEnu[0] = camera.x;
  request_.cameraEnu[1] = camera.y;
  request_.cameraEnu[2] = camera.z;
  return request_;
}

void TreeField::fillCanopy(const glm::dvec3& cameraEnu, vegetation::CanopyTable& out) {
  // The table's window: kCanopyCells cells about the camera's, in tiles.
  const auto n = static_cast<int32_t>(options_.tileCells);
  constexpr auto kHalf = static_cast<int32_t>(vegetation::kCanopyCells / 2);
  const int32_t cx = vegetation::treeCellOf(grid_, cameraEnu.x), cy = vegetation::treeCellOf(grid_, cameraEnu.y);
  auto tileOf = [&](int32_t cell) { return cell >= 0 ? cell / n : -((-cell + n - 1) / n); };
  canopyTrees_.clear();
  for (int32_t ty = tileOf(cy - kHalf); ty <= tileOf(cy + kHalf); ++ty)
    for (int32_t tx = tileOf(cx - kHalf); tx <= tileOf(cx + kHalf); ++tx) {
      const auto it = tiles_.find({tx, ty});
      if (it == tiles_.end() || it->second.pages.empty()) continue;  // not drawn: no crown to thin under
      for (const render::TreeInstanceGpu& t : it->second.trees)
        canopyTrees_.push_back({{t.position[0], t.position[1], t.position[2]}, t.crownM});
    }
  vegetation::fillCanopyTable(grid_, cameraEnu, canopyTrees_, out);
}

}  // namespace vegstream::scene
