// The input triangles' bounding boxes in a uniform grid: which triangles can come within a
// distance of a point or a box, without a scan of all of them. Boundary recovery asks it for
// every Steiner candidate (is the position on the input surface?) and for the triangles that
// a stuck item's may touch; a scan made those linear in the surface per question, so
// quadratic on large parts with many Steiner points.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace tetmesher
{

class TriangleBoxGrid
{
public:
  using Box = std::array<double, 6>; // min x, y, z, max x, y, z

  // boxes: one per triangle, finite.
  explicit TriangleBoxGrid(const std::vector<Box>& boxes);

  // The triangles whose boxes may meet `box` grown by `margin` on every side, in increasing
  // id order, each once (into `out`, cleared first). Never misses one: the cells of a box
  // and of a query are found by the same monotone rounding.
  void near(const Box& box, double margin, std::vector<std::int32_t>& out) const;

private:
  void cellRange(const Box& box, double margin, int lo[3], int hi[3]) const;

  double origin_[3] = { 0, 0, 0 };
  double cellSize_ = 1;
  int dims_[3] = { 1, 1, 1 };
  std::vector<std::int32_t> cellStart_;     // triangles of cell c: [cellStart_[c], cellStart_[c+1])
  std::vector<std::int32_t> cellItems_;     // triangle ids, increasing within a cell
  std::vector<std::int32_t> everywhere_;    // triangles spanning too many cells, tested always
  mutable std::vector<std::uint32_t> seen_; // per triangle, the query that last listed it
  mutable std::uint32_t query_ = 0;
};

} // namespace tetmesher
