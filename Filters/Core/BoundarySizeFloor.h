// A floor under the size field next to boundary faces larger than the wanted size. The
// boundary is never split, so a face of edge L needs a tet of height ~0.8 L on it; when h is
// much smaller (a unit cube of 0.14-edge triangles meshed at h = 0.03), points of size h right
// next to the face make flat tets no optimisation lifts (spikes from a surface vertex to the
// first layer of interior points), and a hard clearance in front of the face only moves the
// problem to the gap it leaves. The floor grades the sizes instead, at the gradation's rate:
//   floor(p) = max over faces F of  s_F - slope * d(p, F),
// s_F the face's size (its vertices' boundary edge sizes), so sizes fall from s_F on the face
// to h at (s_F - h) / slope, and the lattice levels and splits fill a graded layer.
#pragma once

#include "EpochHashTable.h"

#include <cstdint>
#include <vector>

namespace tetmesher
{

class BoundarySizeFloor
{
public:
  BoundarySizeFloor() = default;

  // Faces are triples of indices into `points` (xyz per point; copied, the array may change
  // afterwards). faceSize: s_F per face; faceBase: the size the floor falls to (e.g. the smallest
  // wanted size at the face's vertices): a face with s_F <= faceBase adds nothing. slope > 0.
  BoundarySizeFloor(const double* points,
    const std::vector<std::int32_t>& faceCorners,
    const std::vector<double>& faceSize,
    const std::vector<double>& faceBase,
    double slope);

  // The floor at p: the largest s_F - slope d(p, F) over the faces that reach p (d below
  // (s_F - base_F) / slope), 0 where none does; at least `atLeast` (faces that cannot beat it
  // are not measured).
  double at(const double* p, double atLeast = 0) const;

  bool empty() const { return faces_.empty(); }
  std::size_t faceCount() const { return faces_.size(); }

private:
  struct Face
  {
    double corner[9]; // xyz of its 3 corners
    double size;      // s_F
    double reach;     // distance at which s_F - slope d falls to the face's base size
    double box[6];
    double normal[3]; // unit normal (0 for a degenerate face) and its offset n . corner 0
    double offset;
  };
  bool cellOf(const double* p, std::int64_t* c) const;
  static std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k);
  void consider(const Face& f, const double* p, double& best) const;

  double slope_ = 1;
  double cell_ = 1;
  double origin_[3] = { 0, 0, 0 };
  std::vector<Face> faces_;
  // Each face is listed in every cell its reach touches, with a bound on its floor over the
  // cell, largest first: a query reads p's cell alone and stops at the first bound that
  // cannot beat what it has. The lists lie end to end in entries_ (cell c's from
  // cellStart_[c] to cellStart_[c + 1]), the cells found by key in a flat table: a map of
  // vectors took 3/4 of the construction in allocations (fandisk at h = 0.0103: 617k
  // entries in 40k cells, 0.18 s).
  struct Entry
  {
    double bound;
    std::int32_t face;
  };
  EpochHashTable<std::uint64_t, std::int32_t, MixHash64> cellIndex_;
  std::vector<std::size_t> cellStart_;
  std::vector<Entry> entries_;
  std::vector<std::int32_t> large_; // faces over kMaxCellsPerFace cells, read by every query
};

} // namespace tetmesher
