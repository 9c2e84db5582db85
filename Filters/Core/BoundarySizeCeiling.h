// A ceiling over the size field next to boundary faces smaller than the wanted size. The
// boundary is never coarsened, so a face of edge s needs tets of about s on it; when h is much
// larger (fandisk, edges 0.02, meshed at h = 0.1), points of size h next to it make flat or
// needle tets (45% of fandisk's tets below Q 0.3 at h = 0.1). The ceiling grades the sizes up
// from the faces' own at the gradation's rate:
//   ceiling(p) = min over faces F of  s_F + slope * d(p, F),
// the mirror of BoundarySizeFloor. Faces sit in a bounding-volume hierarchy whose nodes keep
// their smallest s_F, so a query visits the few faces that can set the minimum.
#pragma once

#include <atomic>
#include <cstdint>
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
  // call it at once (the refinement's two halves do): the cache of per-cell lower bounds it
  // fills holds atomic entries, and a cell's bound is the same whoever computes it first.
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
  double cellLowerBound(const double* cellBox) const;
  // The tree search both use: from `best`, nodes whose smallest size plus slope times
  // boxDistance(node box) cannot go below it are skipped, and each face of a leaf gives
  // best = faceValue(face, best).
  template<typename BoxDistance, typename FaceValue>
  double search(double best, const BoxDistance& boxDistance, const FaceValue& faceValue) const;

  // Most queries return atMost (femur.off: 91% of 1.6M): no face comes below it, yet the tree
  // search walks ~40 nodes to show it. A lattice of cells keeps, computed on first use, the
  // smallest s_F + slope * (distance from the cell's box to F's box) over the faces: a lower
  // bound of every bound the search tests for a point of the cell, so when it is not below
  // atMost the search would measure no face and return atMost.
  double cellOrigin_[3] = { 0, 0, 0 };
  double cellSize_ = 0;
  std::int32_t cellDims_[3] = { 0, 0, 0 };
  // 0: not yet computed (bounds are > 0). Relaxed atomics: two threads that compute a cell's
  // bound at once store the same value, and a reader sees 0 (and computes it) or that value.
  mutable std::vector<std::atomic<double>> cellBound_;

  double slope_ = 1;
  std::vector<Face> faces_;
  std::vector<Node> nodes_;
};

} // namespace tetmesher
