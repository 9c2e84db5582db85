#include "TriangleBoxGrid.h"

#include <algorithm>
#include <cmath>

namespace tetmesher
{
namespace
{
// A triangle whose box covers more cells than this goes to the list tested on every query
// (long sliver triangles of CAD parts), so building stays O(triangles).
constexpr std::int64_t kMaxCellsPerTriangle = 64;
constexpr int kMaxDim = 1024;
} // namespace

TriangleBoxGrid::TriangleBoxGrid(const std::vector<Box>& boxes)
{
  const std::size_t count = boxes.size();
  seen_.assign(count, 0);
  if (count == 0)
    return;
  Box bounds = boxes[0];
  for (const Box& b : boxes)
    for (int a = 0; a < 3; ++a)
    {
      bounds[a] = std::min(bounds[a], b[a]);
      bounds[a + 3] = std::max(bounds[a + 3], b[a + 3]);
    }
  // About one cell per triangle; a flat or thin surface gets its thin extent floored so that
  // the other axes are not cut into more cells than triangles.
  double extent[3], longest = 0;
  for (int a = 0; a < 3; ++a)
  {
    extent[a] = bounds[a + 3] - bounds[a];
    longest = std::max(longest, extent[a]);
  }
  if (!(longest > 0))
    longest = 1;
  double volume = 1;
  for (double e : extent)
    volume *= std::max(e, longest / kMaxDim);
  cellSize_ = std::cbrt(volume / static_cast<double>(count));
  if (!(cellSize_ > 0) || !std::isfinite(cellSize_))
    cellSize_ = longest;
  for (int a = 0; a < 3; ++a)
  {
    origin_[a] = bounds[a];
    const double cells = std::ceil(extent[a] / cellSize_);
    dims_[a] = static_cast<int>(std::clamp(cells, 1.0, static_cast<double>(kMaxDim)));
  }
  const std::size_t cellCount = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
  cellStart_.assign(cellCount + 1, 0);
  auto forCells = [&](const Box& b, auto&& visit)
  {
    int lo[3], hi[3];
    cellRange(b, 0, lo, hi);
    const std::int64_t cells =
      static_cast<std::int64_t>(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
    if (cells > kMaxCellsPerTriangle)
      return false;
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x)
          visit((static_cast<std::size_t>(z) * dims_[1] + y) * dims_[0] + x);
    return true;
  };
  for (std::size_t i = 0; i < count; ++i)
    if (!forCells(boxes[i], [&](std::size_t c) { ++cellStart_[c + 1]; }))
      everywhere_.push_back(static_cast<std::int32_t>(i));
  for (std::size_t c = 0; c < cellCount; ++c)
    cellStart_[c + 1] += cellStart_[c];
  cellItems_.resize(static_cast<std::size_t>(cellStart_[cellCount]));
  std::vector<std::int64_t> next(cellStart_.begin(), cellStart_.end() - 1);
  for (std::size_t i = 0; i < count; ++i)
    forCells(boxes[i],
      [&](std::size_t c)
      { cellItems_[static_cast<std::size_t>(next[c]++)] = static_cast<std::int32_t>(i); });
}

void TriangleBoxGrid::cellRange(const Box& box, double margin, int lo[3], int hi[3]) const
{
  for (int a = 0; a < 3; ++a)
  {
    // floor((v - origin) / size) is monotone in v, for the boxes and the queries alike.
    // A NaN bound takes the whole axis (a superset is never wrong).
    const double low = std::floor((box[a] - margin - origin_[a]) / cellSize_);
    const double high = std::floor((box[a + 3] + margin - origin_[a]) / cellSize_);
    const double last = static_cast<double>(dims_[a] - 1);
    lo[a] = std::isnan(low) ? 0 : static_cast<int>(std::clamp(low, 0.0, last));
    hi[a] = std::isnan(high) ? dims_[a] - 1 : static_cast<int>(std::clamp(high, 0.0, last));
  }
}

void TriangleBoxGrid::near(const Box& box, double margin, std::vector<std::int32_t>& out) const
{
  out.clear();
  if (seen_.empty())
    return;
  if (++query_ == 0)
  {
    std::fill(seen_.begin(), seen_.end(), 0u);
    query_ = 1;
  }
  auto take = [&](std::int32_t i)
  {
    if (seen_[static_cast<std::size_t>(i)] != query_)
    {
      seen_[static_cast<std::size_t>(i)] = query_;
      out.push_back(i);
    }
  };
  for (std::int32_t i : everywhere_)
    take(i);
  int lo[3], hi[3];
  cellRange(box, margin, lo, hi);
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x)
      {
        const std::size_t c = (static_cast<std::size_t>(z) * dims_[1] + y) * dims_[0] + x;
        for (std::int64_t k = cellStart_[c]; k < cellStart_[c + 1]; ++k)
          take(cellItems_[static_cast<std::size_t>(k)]);
      }
  std::sort(out.begin(), out.end());
}

} // namespace tetmesher
