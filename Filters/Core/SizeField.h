// The size field h(P) of the paper (George-Hecht-Saltel 1990, section 4.1): the wanted edge
// length at a point. Known at the vertices (given, or by default the mean length of the
// boundary edges at each boundary vertex), interpolated inside a tet with the paper's power
// mean, scaled and clamped by the user, and bounded in growth (gradation) so that sizes change
// smoothly away from small features.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace tetmesher
{

struct SizeFieldOptions
{
  double scale = 1.0; // every size is multiplied by this (before clamping)
  double minSize = 0; // lower bound on h (0: none)
  double maxSize = 0; // upper bound on h (0: none)
  // Gradation g: between two vertices i, j, h_j <= h_i + (g - 1) * |ij|, so the ratio of the
  // sizes of neighbours one h apart is at most g (as Gmsh's / MMG's hgrad). <= 1: off.
  double gradation = 1.5;
  double interpolationPower = 1.0; // p of the paper; 0 gives the geometric mean
};

// Per-vertex h for a triangulated surface: the mean length of the distinct edges at each
// vertex. Vertices in no triangle get 0 (unknown).
std::vector<double> boundaryEdgeSizes(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount);

// Barycentric coordinates of p in the tet `corners` (unclamped), in floating point: for
// interpolation and point placement, never for a topological decision. False (b untouched)
// when the tet's volume is 0 or not finite in doubles.
bool barycentricCoordinates(const double* p, const double* const corners[4], double b[4]);

// h(P) inside a tet from its 4 vertex sizes: (sum b_i h_i^p)^(1/p), b_i the barycentric
// coordinates of p (negative ones, for a point slightly outside, are clamped to 0). p = 0 is
// the limit, the weighted geometric mean. A flat tet uses equal weights. Sizes must be > 0.
double interpolateSize(const double* p,
  const double* const corners[4],
  const double h[4],
  double power);

// The same from p's barycentric coordinates b (as barycentricCoordinates gives them; nullptr
// for a flat tet): for callers that have them already.
double interpolateSizeWithCoordinates(const double* b, const double h[4], double power);

// scale * h, clamped to [minSize, maxSize] (the bounds that are set).
double scaleAndClampSize(double h, const SizeFieldOptions& options);

// Enforces the gradation on a graph with symmetric adjacency in CSR form (neighbours of v are
// targets[offsets[v] .. offsets[v+1])): afterwards h[j] <= h[i] + (g - 1) * |ij| for every
// edge, with sizes only ever lowered (h_j = min over i of h_i + (g-1) * graph distance).
// Returns the number of sizes lowered. Does nothing when gradation <= 1.
// seeds (seedCount of them): when set, only these vertices start the propagation. Valid when
// every edge without a seed end already satisfies the bound (e.g. seeds = the ends of the
// edges added since the last call): the result is then the same as from every vertex.
std::int64_t limitGradation(const double* points,
  std::int32_t pointCount,
  const std::int32_t* offsets,
  const std::int32_t* targets,
  double gradation,
  double* h,
  const std::int32_t* seeds = nullptr,
  std::int32_t seedCount = 0);

// The same from `seeds`, over the adjacency that neighbours(v, list) gives (fills `list`;
// returns false to stop, e.g. when it cannot tell v's neighbours: the sizes lowered so far are
// then restored and -1 returned). Each seed is first lowered from its neighbours, so a vertex
// whose only edges beyond the bound are to seeds need not be one. `lowered` gets every vertex
// whose size was lowered. Given the same edges, the sizes come out bit for bit as from
// limitGradation.
std::int64_t limitGradationFrom(const double* points,
  std::int32_t pointCount,
  double gradation,
  double* h,
  const std::vector<std::int32_t>& seeds,
  const std::function<bool(std::int32_t, std::vector<std::int32_t>&)>& neighbours,
  std::vector<std::int32_t>& lowered);

} // namespace tetmesher
