// The triangle box grid (TriangleBoxGrid.h) against a scan of every box: it must list every
// box that meets the query (grown by the margin), in increasing order, each once.
#include "TriangleBoxGrid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

namespace
{
using tetmesher::TriangleBoxGrid;
using Box = TriangleBoxGrid::Box;

bool meets(const Box& a, const Box& b, double margin)
{
  for (int k = 0; k < 3; ++k)
    if (a[k] > b[k + 3] + margin || b[k] > a[k + 3] + margin)
      return false;
  return true;
}

// Every box the scan finds is listed; the list is sorted and without repeats.
void expectCovers(const std::vector<Box>& boxes, const Box& query, double margin)
{
  TriangleBoxGrid grid(boxes);
  std::vector<std::int32_t> listed;
  grid.near(query, margin, listed);
  ASSERT_TRUE(std::is_sorted(listed.begin(), listed.end()));
  ASSERT_EQ(std::adjacent_find(listed.begin(), listed.end()), listed.end());
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    if (!meets(boxes[i], query, margin))
      continue;
    ASSERT_TRUE(std::binary_search(listed.begin(), listed.end(), static_cast<std::int32_t>(i)))
      << "box " << i << " meets the query but is not listed";
  }
}

// Random boxes: small ones, long slivers across the domain (listed everywhere), and a flat
// set (all z equal: a planar CAD face), queried at points, at box corners exactly, and by
// boxes with margins; queries outside the domain too.
TEST(TriangleBoxGrid, ListsEveryBoxTheScanFinds)
{
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int flat = 0; flat < 2; ++flat)
  {
    std::vector<Box> boxes;
    for (int i = 0; i < 3000; ++i)
    {
      const double size = i % 50 == 0 ? 0.9 : 0.01 + 0.02 * unit(random);
      Box b;
      for (int k = 0; k < 3; ++k)
      {
        b[k] = unit(random);
        b[k + 3] = b[k] + size * unit(random);
      }
      if (flat)
        b[2] = b[5] = 0.25;
      boxes.push_back(b);
    }
    for (int q = 0; q < 400; ++q)
    {
      Box query;
      for (int k = 0; k < 3; ++k)
        query[k] = query[k + 3] = -0.2 + 1.4 * unit(random);
      if (flat && q % 2)
        query[2] = query[5] = 0.25;
      if (q % 3 == 0)
        query = { boxes[q][3], boxes[q][4], boxes[q][5], boxes[q][3], boxes[q][4], boxes[q][5] };
      if (q % 5 == 0)
        for (int k = 0; k < 3; ++k)
          query[k + 3] += 0.05 * unit(random);
      expectCovers(boxes, query, q % 4 == 0 ? 0.0 : q % 7 == 0 ? 0.05 : 1e-6 * q);
    }
  }
}

TEST(TriangleBoxGrid, DegenerateSetsAreListedToo)
{
  // One box, all boxes at one point, and none.
  expectCovers({ Box{ 1, 2, 3, 4, 5, 6 } }, Box{ 4, 5, 6, 4, 5, 6 }, 0);
  expectCovers(std::vector<Box>(100, Box{ 1, 1, 1, 1, 1, 1 }), Box{ 1, 1, 1, 1, 1, 1 }, 0);
  expectCovers({}, Box{ 0, 0, 0, 1, 1, 1 }, 1);
}

} // namespace
