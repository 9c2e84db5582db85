// Where to split a set of points in two halves of space for two threads (the Delaunay kernel's
// halves, MeshHalves' callers): the axis of their longest extent and their median along it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

namespace tetmesher
{

// pointOf(i) gives the coordinates (3 doubles) of point i < count (count > 0).
template<typename PointOf>
void medianSplit(std::size_t count, const PointOf& pointOf, int& axis, double& split)
{
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k)
  {
    lo[k] = std::numeric_limits<double>::max();
    hi[k] = std::numeric_limits<double>::lowest();
  }
  for (std::size_t i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], pointOf(i)[k]);
      hi[k] = std::max(hi[k], pointOf(i)[k]);
    }
  axis = 0;
  for (int k = 1; k < 3; ++k)
    if (hi[k] - lo[k] > hi[axis] - lo[axis])
      axis = k;
  std::vector<double> values(count);
  for (std::size_t i = 0; i < count; ++i)
    values[i] = pointOf(i)[axis];
  std::nth_element(
    values.begin(), values.begin() + static_cast<std::ptrdiff_t>(count / 2), values.end());
  split = values[count / 2];
}

} // namespace tetmesher
