#include "SmallLattice.h"

#include "BinaryParts.h"
#include "ExpansionArithmetic.h"

#include <cmath>
#include <limits>

namespace tetmesher
{

namespace
{
constexpr int kMaxBits = 9; // 72 * 2^(5 * 9) < 2^53: see SmallLattice.h
} // namespace

int smallLatticeBits(const double* points, VertexId n, const double lo[3])
{
  int lowest = std::numeric_limits<int>::max(), highest = std::numeric_limits<int>::min();
  for (std::size_t i = 0; i < 3 * static_cast<std::size_t>(n); ++i)
  {
    const int k = static_cast<int>(i % 3);
    double offset, tail;
    expansion::twoDiff(points[i], lo[k], offset, tail);
    if (tail != 0.0 || !std::isfinite(offset))
      return 0;
    if (offset == 0.0)
      continue;
    binaryParts(offset, lowest, highest);
    if (highest - lowest + 1 > kMaxBits)
      return 0;
  }
  if (lowest == std::numeric_limits<int>::max())
    return 0;
  // Products of up to five differences stay normal doubles and far from overflow, so that
  // "no operation rounds" holds at the ends of the range too.
  if (lowest < -200 || highest > 200)
    return 0;
  return highest - lowest + 1;
}

} // namespace tetmesher
