// A drawn leaf → its vertices and triangle (roam_leaves.h), for the direct output and for the
// drawn chunks alike, so both draw the same triangles.

#include "terrain/roam_leaves.h"

namespace vegstream::terrain {

bool emitLeaf(const RoamMesh& mesh, double timeS, uint32_t t, const LeafSink& sink) {
  assert((sink.morphing == nullptr) == (sink.chunkVertices == nullptr) && "a chunk brings its vertex map");
  const RoamNode& n = mesh.node(t);
  ++sink.counts->leaves;
  for (uint32_t v : n.v)
    if (!(mesh.vertex(v).heightM == mesh.vertex(v).heightM)) return false;  // nodata: a hole, never a drop to 0
  // 2^(z − gridZoom), exactly (a piece's zoom is below the grid's): the tile's uv per grid step.
  assert(!sink.tile || sink.tile->z < mesh.grid().gridZoom());
  const double uvScale =
      sink.tile ? 1.0 / static_cast<double>(uint64_t{1} << (mesh.grid().gridZoom() - sink.tile->z)) : 0.0;
  const double fade = mesh.options().fadeS;
  for (uint32_t v : n.v) {
    uint32_t* known = nullptr;  // the chunk's entry for v
    if (sink.chunkVertices) {
      known = &sink.chunkVertices->at(v);
      if (*known != kNoNode) {
        sink.indices->push_back(*known);
        continue;
      }
    } else if (const VertexStamp& st = (*sink.stamps)[v]; st.frame == sink.frame && st.piece == sink.stamp) {
      sink.indices->push_back(st.index);
      continue;
    }
    const RoamVertex& x = mesh.vertex(v);
    const double h = x.drawnHeight(timeS, fade);
    if (h != x.heightM) ++sink.counts->morphingVertices;
    TerrainVertex out;
    out.position = glm::vec3(x.position(h) - sink.origin);
    out.normal = x.normal;
    out.heightMsl = static_cast<float>(h);
    if (sink.tile)
      out.uv = glm::vec2(double(x.grid.x) * uvScale - sink.tile->x, double(x.grid.y) * uvScale - sink.tile->y);
    const auto index = static_cast<uint32_t>(sink.vertices->size());
    if (known)
      *known = index;
    else
      (*sink.stamps)[v] = {sink.frame, sink.stamp, index};
    if (sink.morphing && !x.morphDone(timeS, fade)) sink.morphing->emplace_back(index, x);
    sink.indices->push_back(index);
    sink.vertices->push_back(out);
  }
  return true;
}

}  // namespace vegstream::terrain
