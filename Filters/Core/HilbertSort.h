// Insertion order for incremental Delaunay: Hilbert curve sorting and BRIO rounds.
//
// Inserting points along a space-filling curve keeps consecutive points close, so the walk
// from the previously created tet is short and memory accesses stay local. BRIO (Amenta,
// Choi, Rote 2003: "biased randomized insertion order") first shuffles the points and splits
// them into rounds of growing size, sorting each round along the curve: the randomness keeps
// the expected cavity sizes small on adversarial input, the sorting keeps locality.
// Everything is deterministic: the shuffle uses a fixed-seed generator of our own.
#pragma once

#include "TetMesh.h"

#include <cstdint>
#include <vector>

namespace tetmesher
{

// Position of a point on the 3D Hilbert curve of order `bits` (<= 21) over the unit grid
// [0, 2^bits)^3; x, y, z are grid coordinates.
std::uint64_t hilbertIndex(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits);

// Sorts the vertex ids in [first, last) along the Hilbert curve of the bounding box of all
// `coords` (3 doubles per vertex). Ties are broken by id, so the order is deterministic.
// twoThreads: large sorts run in halves on two threads (the same order).
void hilbertSort(const double* coords, VertexId* first, VertexId* last, bool twoThreads = false);

// Returns ids 0..n-1 in BRIO order: shuffled with the given seed, split into rounds (each
// round about 1/ratio times the previous one), each round Hilbert-sorted. roundStarts, when
// given, receives the position of each round's first id, in order (the first is 0).
std::vector<VertexId> brioOrder(const double* coords,
  VertexId n,
  std::uint64_t seed = 0x5eed5eedULL,
  std::vector<std::size_t>* roundStarts = nullptr,
  bool twoThreads = false);

} // namespace tetmesher
