#pragma once
// A tile-selection node's box and geometric error (tile_selection.h), and a memo of them.
//
// nodeBox() holds the node's surface at any height in [hMin, hMax] in one local ENU frame: its
// corners, edge midpoints and centre at both heights through the exact geodetic → ENU map,
// padded for the curvature between those points. That is 18 projections a node (most of a
// selection's time: 8.8 % of the terrain's frame-thread instructions on benchmark-30s at low
// altitude, callgrind), and the same every frame for a node whose height range stays the same.
//
// NodeBoxes memoizes nodeBox() and the geometric error by TileId for one frame. Contract:
// - at() returns exactly what nodeBox(id, hMin, hMax, frame) and nodeGeometricErrorM(id) return
//   (a hit whose height range differs is computed again), so a selection made with a memo is the
//   same, bit for bit, as one made without;
// - every call passes the same frame (checked in debug builds by its origin);
// - it holds at most `capacity` nodes: when full it starts again empty (the values do not
//   depend on what is held, only the time does);
// - not thread-safe: one memo per thread of selections (StreamedTerrain keeps one per pose).

#include <cstddef>
#include <unordered_map>

#include <glm/vec3.hpp>

#include "geo/local_frame.h"
#include "geo/xyz_tiles.h"

namespace vegstream::terrain {

struct NodeBox {
  glm::dvec3 lo{0.0}, hi{0.0};  // ENU metres
  double errorM = 0.0;          // nodeGeometricErrorM of the node
};

// The box (errorM included) of node `t` with heights in [hMin, hMax], in `frame`.
NodeBox nodeBox(const geo::TileId& t, double hMin, double hMax, const geo::LocalFrame& frame);

class NodeBoxes {
 public:
  static constexpr size_t kDefaultCapacity = size_t{1} << 14;  // about 2 MB
  explicit NodeBoxes(size_t capacity = kDefaultCapacity) : capacity_(capacity) {}

  const NodeBox& at(const geo::TileId& t, double hMin, double hMax, const geo::LocalFrame& frame);

  size_t size() const { return boxes_.size(); }
  // Lookups answered from the memo and computed, since construction.
  size_t hits() const { return hits_; }
  size_t misses() const { return misses_; }

 private:
  struct Entry {
    double hMin, hMax;
    NodeBox box;
  };
  size_t capacity_;
  std::unordered_map<geo::TileId, Entry> boxes_;
  geo::Geodetic origin_{};  // the frame's (debug check)
  size_t hits_ = 0, misses_ = 0;
};

}  // namespace vegstream::terrain
