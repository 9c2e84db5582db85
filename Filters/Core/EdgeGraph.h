// The unique edges of a mesh's live tets as a symmetric CSR adjacency, each entry with a tet
// that has the edge: the refinement's edge splitting and size gradation walk it after every
// round. Linear time: half edges are bucketed by their smaller vertex (counting sort, a chunk of
// vertices at a time), duplicates dropped with a stamp per vertex. Large meshes are built in two
// halves side by side (tets, then vertex ranges); the arrays are the same either way.
#pragma once

#include "TetMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tetmesher
{

class EdgeGraph
{
public:
  // Rebuilds from the live tets of `mesh`, on two threads when twoThreads and the mesh is large.
  void build(const TetMesh& mesh, bool twoThreads);

  // The neighbours of v are targets[offsets[v] .. offsets[v + 1]): first the smaller ones in
  // increasing order, then the larger ones in the order of the first tet (by id) that has the
  // edge; tetOf[k] is a tet with edge (v, targets[k]) (for a smaller neighbour u, the one of u's
  // entry).
  std::vector<std::int32_t> offsets;
  std::vector<VertexId> targets;
  std::vector<TetId> tetOf;

  // The half edges (6 per tet) are sorted in chunks of vertices with at most this many: the
  // scratch holds one chunk (10 bytes per half edge). The arrays do not depend on it.
  std::size_t chunkHalfEdges = std::size_t{ 1 } << 21;
  // ... or with up to 1 / maxChunks of all half edges, when that is more: every chunk reads
  // every tet again, and on large meshes those scans were most of the build (cgal_bunny00.off
  // at its default size, 5.3M tets: 16 chunks, 0.44 and 0.74 s for two builds; 4 chunks, 0.27
  // and 0.35 s, peak memory unchanged). Below 4 * 2^21 half edges (350k tets) nothing changes.
  std::size_t maxChunks = 4;

private:
  // Scratch of one half of the work.
  struct Half
  {
    std::vector<std::int32_t> count, fill, incoming, cursor;
    std::vector<VertexId> stamp, blockTarget;
    std::vector<TetId> blockTet;
    std::vector<std::int32_t> vertexFill;
  };
  std::vector<std::int32_t> start_, unique_;
  Half half_[2];
};

} // namespace tetmesher
