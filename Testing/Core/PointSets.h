// Point sets for the Delaunay kernel's tests: uniform random, nearly co-spherical, and a fully
// degenerate grid, each deterministic.
#pragma once

#include "TetMesh.h"

#include <cmath>
#include <random>

namespace tetmesher
{
namespace testing
{

inline TetMesh randomPoints(int n, unsigned seed, double lo = 0, double hi = 1)
{
  TetMesh mesh;
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  for (int i = 0; i < n; ++i)
    mesh.addVertex(u(gen), u(gen), u(gen));
  return mesh;
}

// n points uniformly spread on the unit sphere (rounded: nearly, not exactly, co-spherical).
inline TetMesh pointsOnUnitSphere(int n, unsigned seed)
{
  TetMesh mesh;
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> g;
  for (int i = 0; i < n; ++i)
  {
    double x = g(gen), y = g(gen), z = g(gen);
    double r = std::sqrt(x * x + y * y + z * z);
    mesh.addVertex(x / r, y / r, z / r);
  }
  return mesh;
}

// The m^3 integer points of a cube: every unit cube's 8 corners are co-spherical.
inline TetMesh gridPoints(int m)
{
  TetMesh mesh;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k)
        mesh.addVertex(i, j, k);
  return mesh;
}

} // namespace testing
} // namespace tetmesher
