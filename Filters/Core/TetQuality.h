// Element quality of the paper (George-Hecht-Saltel 1990, section 4.2):
//   Q(T) = k * r / lmax,  k = 2*sqrt(6)
// with r the inradius and lmax the longest edge, so that the regular tet has Q = 1 and a flat
// tet Q = 0. Also the dihedral angles that users of other meshers compare against.
//
// Size-scaled variant (h given at the 4 vertices): lengths are measured in units of h. An
// edge AB counts 0.5 * (l/h(A) + l/h(B)) as in the paper; the inradius, which belongs to
// no edge, is measured in the harmonic mean of the four h (the same averaging of 1/h).
// For constant h both reduce to the classical Q.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tetmesher
{

constexpr double kQualityScale = 4.898979485566356; // 2*sqrt(6)

struct TetShape
{
  double quality = 0;      // k r / lmax in [0, 1]; 0 for flat or inverted tets
  double minDihedral = 0;  // degrees
  double maxDihedral = 0;  // degrees
  double signedVolume = 0; // det[b-a, c-a, d-a] / 6: > 0 in VTK's VTK_TETRA orientation
                           // (the right-hand normal of a,b,c points to d). Note: that
                           // is orient3d < 0 in Shewchuk's sign, TetMesh's convention.
};

// det[b-a, c-a, d-a] / 6 in doubles: TetShape::signedVolume, computed the same way (VTK order).
inline double tetSignedVolume(const double* a, const double* b, const double* c, const double* d)
{
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  const double w[3] = { d[0] - a[0], d[1] - a[1], d[2] - a[2] };
  const double x[3] = {
    v[1] * w[2] - v[2] * w[1], v[2] * w[0] - v[0] * w[2], v[0] * w[1] - v[1] * w[0]
  };
  return (u[0] * x[0] + u[1] * x[1] + u[2] * x[2]) / 6.0;
}

// True when det[b-a, c-a, d-a] (VTK order) is positive beyond doubt in double precision: both
// from a (as tetSignedVolume rounds it) and from d, it exceeds its rounding error bound
// (Shewchuk's orient3d filter: (7 + 56 eps) eps times the sum of the terms' magnitudes). A tet
// that fails it may round to a zero or negative volume in another evaluation order (a solver's
// Jacobian, another tool's quality filter) even where tetSignedVolume is positive.
bool volumeCertainlyPositive(const double* a, const double* b, const double* c, const double* d);

// Shape of the tet (a,b,c,d) in VTK order. Quality is 0 when signedVolume is not positive.
TetShape measureTet(const double* a, const double* b, const double* c, const double* d);

// measureTet(a, b, c, d).quality bit for bit, without the dihedral angles (half the work).
double measureTetQuality(const double* a, const double* b, const double* c, const double* d);

// As measureTet, but Q in units of the size field: h[i] is the wanted size at vertex i (> 0).
TetShape measureTetScaled(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double h[4]);

// measureTet (h null) or measureTetScaled (h given), with maxDihedral left 0 unless asked
// for: one arc cosine fewer per tet in the optimiser's inner loops. The other fields are
// the same bit for bit.
TetShape measureTetForOptimization(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* h,
  bool withMaxDihedral = false);

// Summary statistics of a set of Q values (the numbers the CLI prints and the filters store).
struct QualitySummary
{
  std::int64_t count = 0;
  double minimum = 0;
  double maximum = 0;
  double mean = 0;
  double percentile1 = 0;  // the 1st percentile (nearest rank)
  double shareBelow01 = 0; // fraction of tets with Q < 0.1
  double shareBelow03 = 0; // fraction of tets with Q < 0.3
  double minDihedral = 0;  // degrees, over all tets
  double maxDihedral = 0;  // degrees, over all tets
};

QualitySummary summarizeQuality(const std::vector<TetShape>& shapes);

// Histogram of Q values over [0, 1] in `binCount` equal bins; Q = 1 falls in the last bin.
std::vector<std::int64_t> qualityHistogram(const std::vector<double>& quality, int binCount);

// The summary as the field data the filters store and the CLI prints, in their order.
std::vector<std::pair<const char*, double>> qualitySummaryFields(const QualitySummary& summary);

// Per-cell quality of a mesh, its summary and histogram (vtkTetQuality's and vtkTetMesher's
// arrays Quality, MinDihedralAngle, MaxDihedralAngle).
struct MeshQuality
{
  std::vector<double> quality;     // per cell; NaN for cells that are not tetrahedra
  std::vector<double> minDihedral; // per cell, degrees
  std::vector<double> maxDihedral; // per cell, degrees
  QualitySummary summary;
  std::vector<std::int64_t> histogram;
};

// A mesh to measure: cells[4c..4c+3] are the point ids of cell c in VTK order, cells[4c] < 0
// for a cell that is not a tetrahedron. `sizes` (optional) is h > 0 per point, named
// `sizeName` in errors.
struct TetMeshView
{
  const double* points = nullptr;
  std::int64_t pointCount = 0;
  const std::int64_t* cells = nullptr;
  std::int64_t cellCount = 0;
  const double* sizes = nullptr;
  std::string sizeName;
};

// Measures every tetrahedron of a mesh. Returns false with `error` naming the defect (no
// tetrahedra, a non-finite coordinate, a bad size value) and where it is.
bool measureMesh(const TetMeshView& mesh, int binCount, MeshQuality& result, std::string& error);

} // namespace tetmesher
