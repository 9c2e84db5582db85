// buildSurfaceInput's first reported defect, TriangleIndex look-ups, and the radix sort that
// replaces std::sort on (key, value) pairs.
#include "RadixSort.h"
#include "SurfaceInput.h"
#include "TriangleIndex.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace
{
// An octahedron (8 triangles) and the unit points of its 6 vertices.
std::vector<double> OctahedronPoints()
{
  return { 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1 };
}
std::vector<std::int32_t> OctahedronTriangles()
{
  return { 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5 };
}
std::string Build(const std::vector<std::int32_t>& triangles)
{
  const std::vector<double> points = OctahedronPoints();
  tetmesher::SurfaceInput surface;
  return tetmesher::buildSurfaceInput(points.data(),
    static_cast<std::int32_t>(points.size() / 3),
    triangles.data(),
    static_cast<std::int32_t>(triangles.size() / 3),
    surface);
}
} // namespace

TEST(SurfaceInput, ValidOctahedron)
{
  EXPECT_EQ(Build(OctahedronTriangles()), "");
}

TEST(SurfaceInput, FirstDuplicateInTriangleOrder)
{
  // Triangle 9 repeats triangle 1 (reversed), triangle 8 repeats triangle 6: the scan in
  // triangle order meets triangle 8 first.
  std::vector<std::int32_t> t = OctahedronTriangles();
  t.insert(t.end(), { 1, 3, 5, 4, 1, 2 });
  EXPECT_EQ(Build(t), "triangles 6 and 8 are duplicates");
  // Three copies of one triangle: the second names the first.
  t = OctahedronTriangles();
  t.insert(t.end(), { 4, 0, 2, 2, 4, 0 });
  EXPECT_EQ(Build(t), "triangles 0 and 8 are duplicates");
}

TEST(SurfaceInput, EarlierDefectWinsOverLaterDuplicate)
{
  // Triangle 8 is degenerate, triangle 9 a duplicate: the degenerate one is reported.
  std::vector<std::int32_t> t = OctahedronTriangles();
  t.insert(t.end(), { 0, 0, 1, 0, 2, 4 });
  EXPECT_EQ(Build(t), "triangle 8 (0,0,1) is degenerate");
  // A duplicate (8) before an id out of range (9): the duplicate is reported.
  t = OctahedronTriangles();
  t.insert(t.end(), { 0, 2, 4, 0, 1, 17 });
  EXPECT_EQ(Build(t), "triangles 0 and 8 are duplicates");
  // An id out of range (8) before a duplicate (9).
  t = OctahedronTriangles();
  t.insert(t.end(), { 0, 1, 17, 0, 2, 4 });
  EXPECT_EQ(Build(t), "triangle 8 references point id 17 out of range [0,6)");
}

TEST(TriangleIndex, FindsEveryTriangleInAnyOrderAndNothingElse)
{
  const std::vector<std::int32_t> t = OctahedronTriangles();
  const tetmesher::TriangleIndex index(t.data(), static_cast<std::int32_t>(t.size() / 3));
  for (std::int32_t i = 0; i < 8; ++i)
  {
    const std::int32_t a = t[3 * i], b = t[3 * i + 1], c = t[3 * i + 2];
    EXPECT_EQ(index.find(a, b, c), i);
    EXPECT_EQ(index.find(c, a, b), i);
    EXPECT_EQ(index.find(b, a, c), i);
  }
  EXPECT_EQ(index.find(0, 1, 2), -1);
  EXPECT_EQ(index.find(0, 2, 99), -1);
  EXPECT_EQ(index.find(99, 100, 101), -1);
  EXPECT_EQ(index.find(-1, 2, 4), -1);
  // Repeated triangles: the lowest id.
  const std::vector<std::int32_t> twice = { 3, 4, 5, 5, 3, 4, 1, 2, 3 };
  const tetmesher::TriangleIndex repeated(twice.data(), 3);
  EXPECT_EQ(repeated.find(4, 5, 3), 0);
  EXPECT_EQ(repeated.find(1, 3, 2), 2);
}

TEST(RadixSort, SameOrderAsStdSortOnPushedPairs)
{
  std::mt19937_64 random(7);
  for (int bits : { 3, 12, 20, 33, 64 })
  {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> pairs;
    for (std::uint32_t i = 0; i < 20000; ++i)
    {
      const std::uint64_t key = bits == 64 ? random() : random() & ((std::uint64_t(1) << bits) - 1);
      pairs.push_back({ key, i }); // values increase in push order
    }
    auto expected = pairs;
    std::sort(expected.begin(), expected.end());
    tetmesher::sortPushedPairs(pairs);
    EXPECT_EQ(pairs, expected) << bits << " key bits";
  }
}
