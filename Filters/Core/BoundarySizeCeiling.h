// A ceiling over the size field next to boundary faces smaller than the wanted size. The
// boundary is never coarsened, so a face of edge s needs tets of about s on it; when h is much
// larger (fandisk, edges 0.02, meshed at h = 0.1), points of size h next to it make flat or
// needle tets (45% of fandisk's tets below Q 0.3 at h = 0.1). The ceiling grades the sizes up
// from the faces' own at the gradation's rate:
//   ceiling(p) = min over faces F of  s_F + slope * d(p, F),
// the mirror of BoundarySizeFloor. Faces sit in a bounding-volume hierarchy whose nodes keep
// their smallest s_F, so a query visits the few faces that can set the minimum; inside the
// faces' box, a lattice of cells lists those faces per cell (below).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

namespace tetmesher
{

class BoundarySizeCeiling
{
public:
  BoundarySizeCeiling() = default;

  // Faces are triples of indices into `points` (xyz per point; copied). faceSize: s_F per face
  // (faces with a size that is not positive and finite are left out). slope > 0.
  BoundarySizeCeiling(const double* points,
    const std::vector<std::int32_t>& faceCorners,
    const std::vector<double>& faceSize,
    double slope);

  // min(atMost, ceiling(p)): faces that cannot go below atMost are not measured. Threads may
  // call it at once (the refinement's two halves do): the per-cell lists it makes on first use
  // (below) are published atomically, and the answer is the same whoever makes them.
  double at(const double* p, double atMost) const;

  bool empty() const { return faces_.empty(); }

private:
  struct Face
  {
    double corner[9]; // xyz of its 3 corners
    double size;
    double box[6];
  };
  struct Node
  {
    double box[6];
    double minSize;
    std::int32_t first, count; // faces [first, first + count) when a leaf (count > 0)
    std::int32_t left, right;  // children when an inner node
  };
  std::int32_t build(std::int32_t first, std::int32_t count);
  // The tree search: from `best`, nodes whose smallest size plus slope times
  // boxDistance(node box) cannot go below it are skipped, and each face of a leaf gives
  // best = faceValue(face, best).
  template<typename BoxDistance, typename FaceValue>
  double search(double best, const BoxDistance& boxDistance, const FaceValue& faceValue) const;
  // min(bound, s_F + slope d(p, F)): F's value at p when it can go below bound.
  double faceValue(const Face& f, const double* p, double bound) const;

  // Most queries return atMost (femur.off: 58% of 2.4M): no face comes below it, yet the tree
  // search walks ~40 nodes to show it, and the others walked as many. A lattice of cells keeps,
  // made on first use, the faces that can give the ceiling somewhere in the cell: those whose
  // lower bound over the cell (s_F + slope * the distance from the cell's box to F's box) is
  // below an upper bound of the ceiling over the cell (its value at the cell's centre plus
  // slope times the half diagonal), by increasing lower bound. A query of the cell returns
  // atMost when the first bound is not below it (then the search would measure no face), else
  // reads the list up to the first bound not below the best value so far. The same answers
  // as the tree search (femur.off's lattice candidates 0.60 -> 0.37 s).
  // A list also stops at `limit`, 1.25 times the atMost of the query that made it: faces whose
  // bound is not below atMost cannot change a query's answer, and far from the small faces
  // (sizes constant near h) the upper bound lets in hundreds of them. A query with a larger
  // atMost makes the list again with its own limit.
  struct CellEntry
  {
    float lower; // rounded down: still a lower bound, in half the memory (8 bytes an entry)
    std::int32_t face;
  };
  struct CellList
  {
    std::vector<CellEntry> entries; // holds the face giving the ceiling at the centre
    // Every face whose bound is below `limit` is listed (infinite: every face that can give
    // the ceiling in the cell). The list it replaced, kept for the threads still reading it.
    double limit = 0;
    std::unique_ptr<CellList> replaced;
  };
  const CellList& cellList(std::size_t cell, const double* cellBox, double atMost) const;
  // A cell's list is made by the first thread that needs it and published by a
  // compare-and-swap (a thread that loses it drops its own and reads the winner's, made again
  // if its limit is too low). Lists may differ with the order of queries; answers do not.
  struct CellLists
  {
    std::unique_ptr<std::atomic<CellList*>[]> slots;
    std::size_t count = 0;
    CellLists() = default;
    explicit CellLists(std::size_t n);
    CellLists(CellLists&&) = default;
    CellLists& operator=(CellLists&& other) noexcept; // frees its own lists first
    ~CellLists();
    void release();
  };
  double cellOrigin_[3] = { 0, 0, 0 };
  double cellSize_ = 0;
  std::int32_t cellDims_[3] = { 0, 0, 0 };
  CellLists cells_;

  double slope_ = 1;
  std::vector<Face> faces_;
  std::vector<Node> nodes_;
};

} // namespace tetmesher
