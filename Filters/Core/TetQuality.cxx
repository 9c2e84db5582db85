#include "TetQuality.h"

#include "FilteredPredicates.h"
#include "ParallelPair.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace tetmesher
{
namespace
{

struct Vec3
{
  double x, y, z;
};

Vec3 sub(const double* p, const double* q)
{
  return { p[0] - q[0], p[1] - q[1], p[2] - q[2] };
}
Vec3 cross(const Vec3& u, const Vec3& v)
{
  return { u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x };
}
double dot(const Vec3& u, const Vec3& v)
{
  return u.x * v.x + u.y * v.y + u.z * v.z;
}
double norm(const Vec3& u)
{
  return std::sqrt(dot(u, u));
}

// det[p-o, q-o, r-o] has the sign `sign` beyond its rounding error in doubles (the orient3d
// filter's bound on this very evaluation: differences, 2x2 minors, then the dot product).
bool signBeyondRounding(const double* o,
  const double* p,
  const double* q,
  const double* r,
  int sign)
{
  const double u[3] = { p[0] - o[0], p[1] - o[1], p[2] - o[2] };
  const double v[3] = { q[0] - o[0], q[1] - o[1], q[2] - o[2] };
  const double w[3] = { r[0] - o[0], r[1] - o[1], r[2] - o[2] };
  const double m[6] = {
    v[1] * w[2], v[2] * w[1], v[2] * w[0], v[0] * w[2], v[0] * w[1], v[1] * w[0]
  };
  const double det = u[0] * (m[0] - m[1]) + u[1] * (m[2] - m[3]) + u[2] * (m[4] - m[5]);
  const double permanent = std::fabs(u[0]) * (std::fabs(m[0]) + std::fabs(m[1])) +
    std::fabs(u[1]) * (std::fabs(m[2]) + std::fabs(m[3])) +
    std::fabs(u[2]) * (std::fabs(m[4]) + std::fabs(m[5]));
  return sign * det > predicates::bounds::kOrient3d * permanent;
}

constexpr double kRadToDeg = 57.29577951308232;
// The 6 edges as vertex pairs, and for each the two faces (by opposite vertex) sharing it.
constexpr int kEdges[6][2] = { { 0, 1 }, { 0, 2 }, { 0, 3 }, { 1, 2 }, { 1, 3 }, { 2, 3 } };

// Everything but the length unit: volume, face areas, dihedral angles, edge lengths.
struct RawShape
{
  double volume;
  double areaSum;
  double edgeLength[6];
  double minDihedral, maxDihedral;
};

// Outward area vectors of the face opposite each vertex (any consistent sign works for
// angles: the dihedral angle at an edge is pi minus the angle between the two normals),
// their lengths, and the volume, area sum and edge lengths of s.
void measureFacesAndEdges(const double* const p[4],
  RawShape& s,
  Vec3 normal[4],
  double normalLength[4])
{
  s.volume = tetSignedVolume(p[0], p[1], p[2], p[3]);
  const int faces[4][3] = { { 1, 2, 3 }, { 0, 3, 2 }, { 0, 1, 3 }, { 0, 2, 1 } };
  for (int f = 0; f < 4; ++f)
  {
    normal[f] = cross(sub(p[faces[f][1]], p[faces[f][0]]), sub(p[faces[f][2]], p[faces[f][0]]));
    normalLength[f] = norm(normal[f]);
    s.areaSum += 0.5 * normalLength[f];
  }
  for (int e = 0; e < 6; ++e)
    s.edgeLength[e] = norm(sub(p[kEdges[e][0]], p[kEdges[e][1]]));
}

RawShape measureRaw(const double* a,
  const double* b,
  const double* c,
  const double* d,
  bool withMaxDihedral = true)
{
  const double* p[4] = { a, b, c, d };
  RawShape s{};
  Vec3 normal[4];
  double normalLength[4];
  measureFacesAndEdges(p, s, normal, normalLength);
  // The dihedral angle 180 - acos(cosine) grows with the cosine, so the extreme angles come
  // from the extreme cosines: two acos per tet instead of six (the same values bit for bit).
  double lowCosine = 2.0, highCosine = -2.0;
  bool degenerate = false;
  for (int e = 0; e < 6; ++e)
  {
    int i = kEdges[e][0], j = kEdges[e][1];
    // The two faces containing edge (i,j) are those opposite the other two vertices.
    int k = -1, l = -1;
    for (int v = 0; v < 4; ++v)
      if (v != i && v != j)
        (k < 0 ? k : l) = v;
    double nk = normalLength[k], nl = normalLength[l];
    if (nk > 0 && nl > 0)
    {
      double cosine = std::clamp(dot(normal[k], normal[l]) / (nk * nl), -1.0, 1.0);
      lowCosine = std::min(lowCosine, cosine);
      highCosine = std::max(highCosine, cosine);
    }
    else
      degenerate = true; // that angle counts as 0
  }
  auto angle = [](double cosine) { return 180.0 - std::acos(cosine) * kRadToDeg; };
  s.minDihedral = 180.0;
  s.maxDihedral = 0.0;
  if (lowCosine <= 1.0)
  {
    s.minDihedral = std::min(s.minDihedral, angle(lowCosine));
    if (withMaxDihedral)
      s.maxDihedral = std::max(s.maxDihedral, angle(highCosine));
  }
  if (degenerate)
    s.minDihedral = std::min(s.minDihedral, 0.0);
  return s;
}

TetShape finish(const RawShape& s, double inradius, double longestEdge)
{
  TetShape shape;
  shape.signedVolume = s.volume;
  shape.minDihedral = s.minDihedral;
  shape.maxDihedral = s.maxDihedral;
  if (s.volume > 0 && longestEdge > 0)
    shape.quality = std::min(1.0, kQualityScale * inradius / longestEdge);
  return shape;
}

} // namespace

bool volumeCertainlyPositive(const double* a, const double* b, const double* c, const double* d)
{
  // From d the same determinant is det[a-d, b-d, c-d] with the opposite sign.
  return signBeyondRounding(a, b, c, d, 1) && signBeyondRounding(d, a, b, c, -1);
}

TetShape measureTet(const double* a, const double* b, const double* c, const double* d)
{
  RawShape s = measureRaw(a, b, c, d);
  double inradius = s.areaSum > 0 ? 3.0 * s.volume / s.areaSum : 0.0;
  double longest = *std::max_element(s.edgeLength, s.edgeLength + 6);
  return finish(s, inradius, longest);
}

double measureTetQuality(const double* a, const double* b, const double* c, const double* d)
{
  const double* p[4] = { a, b, c, d };
  RawShape s{};
  Vec3 normal[4];
  double normalLength[4];
  measureFacesAndEdges(p, s, normal, normalLength);
  double inradius = s.areaSum > 0 ? 3.0 * s.volume / s.areaSum : 0.0;
  double longest = *std::max_element(s.edgeLength, s.edgeLength + 6);
  return finish(s, inradius, longest).quality;
}

TetShape measureTetScaled(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double h[4])
{
  return measureTetForOptimization(a, b, c, d, h, true);
}

TetShape measureTetForOptimization(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* h,
  bool withMaxDihedral)
{
  RawShape s = measureRaw(a, b, c, d, withMaxDihedral);
  if (!h)
  {
    double inradius = s.areaSum > 0 ? 3.0 * s.volume / s.areaSum : 0.0;
    double longest = *std::max_element(s.edgeLength, s.edgeLength + 6);
    return finish(s, inradius, longest);
  }
  double longest = 0.0, inverseSum = 0.0;
  for (int e = 0; e < 6; ++e)
  {
    double l = s.edgeLength[e];
    longest = std::max(longest, 0.5 * (l / h[kEdges[e][0]] + l / h[kEdges[e][1]]));
  }
  for (int i = 0; i < 4; ++i)
    inverseSum += 1.0 / h[i];
  double inradius = s.areaSum > 0 ? 3.0 * s.volume / s.areaSum : 0.0;
  // Inradius in units of the harmonic mean of h: r / hmean = r * (sum 1/h_i) / 4.
  return finish(s, inradius * inverseSum / 4.0, longest);
}

namespace
{
// The summary of `count` tets, shape(n) giving tet n's TetShape (only Q and the dihedral
// angles are read).
template<typename Shape>
QualitySummary summarizeOf(std::size_t count, const Shape& shape)
{
  QualitySummary summary;
  summary.count = static_cast<std::int64_t>(count);
  if (count == 0)
    return summary;
  std::vector<double> q;
  q.reserve(count);
  double sum = 0.0;
  std::int64_t below01 = 0, below03 = 0;
  summary.minDihedral = 180.0;
  summary.maxDihedral = 0.0;
  for (std::size_t n = 0; n < count; ++n)
  {
    const TetShape s = shape(n);
    q.push_back(s.quality);
    sum += s.quality;
    below01 += s.quality < 0.1;
    below03 += s.quality < 0.3;
    summary.minDihedral = std::min(summary.minDihedral, s.minDihedral);
    summary.maxDihedral = std::max(summary.maxDihedral, s.maxDihedral);
  }
  std::size_t rank = (q.size() + 99) / 100; // nearest rank of the 1st percentile, >= 1
  std::nth_element(q.begin(), q.begin() + static_cast<std::ptrdiff_t>(rank - 1), q.end());
  summary.percentile1 = q[rank - 1];
  summary.minimum = *std::min_element(q.begin(), q.end());
  summary.maximum = *std::max_element(q.begin(), q.end());
  summary.mean = sum / static_cast<double>(q.size());
  summary.shareBelow01 = static_cast<double>(below01) / static_cast<double>(q.size());
  summary.shareBelow03 = static_cast<double>(below03) / static_cast<double>(q.size());
  return summary;
}
} // namespace

QualitySummary summarizeQuality(const std::vector<TetShape>& shapes)
{
  return summarizeOf(shapes.size(), [&](std::size_t n) { return shapes[n]; });
}

namespace
{
template<typename Quality>
std::vector<std::int64_t> histogramOf(std::size_t count, int binCount, const Quality& quality)
{
  std::vector<std::int64_t> bins(static_cast<std::size_t>(std::max(binCount, 1)), 0);
  for (std::size_t n = 0; n < count; ++n)
  {
    int bin = static_cast<int>(quality(n) * static_cast<double>(bins.size()));
    bin = std::clamp(bin, 0, static_cast<int>(bins.size()) - 1);
    ++bins[static_cast<std::size_t>(bin)];
  }
  return bins;
}
} // namespace

std::vector<std::int64_t> qualityHistogram(const std::vector<double>& quality, int binCount)
{
  return histogramOf(quality.size(), binCount, [&](std::size_t n) { return quality[n]; });
}

std::vector<std::pair<const char*, double>> qualitySummaryFields(const QualitySummary& summary)
{
  return { { "TetrahedronCount", static_cast<double>(summary.count) },
    { "QualityMinimum", summary.minimum },
    { "QualityMean", summary.mean },
    { "QualityPercentile1", summary.percentile1 },
    { "QualityShareBelow0.1", summary.shareBelow01 },
    { "QualityShareBelow0.3", summary.shareBelow03 },
    { "MinDihedralAngle", summary.minDihedral },
    { "MaxDihedralAngle", summary.maxDihedral } };
}

bool measureMesh(const TetMeshView& mesh, int binCount, MeshQuality& result, std::string& error)
{
  const double* sizes = mesh.sizes;
  for (std::int64_t p = 0; p < mesh.pointCount; ++p)
  {
    const double* x = mesh.points + 3 * p;
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
    {
      std::ostringstream message;
      message << "point " << p << " has a non-finite coordinate (" << x[0] << ", " << x[1] << ", "
              << x[2] << ")";
      error = message.str();
      return false;
    }
    if (sizes && (!(sizes[p] > 0) || !std::isfinite(sizes[p])))
    {
      std::ostringstream message;
      message << "size array '" << mesh.sizeName << "' has the invalid value " << sizes[p]
              << " at point " << p << " (sizes must be finite and > 0)";
      error = message.str();
      return false;
    }
  }

  const auto count = static_cast<std::size_t>(mesh.cellCount);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  result.quality.assign(count, nan);
  result.minDihedral.assign(count, nan);
  result.maxDihedral.assign(count, nan);
  // The tet cells, listed only when some cell is not one (vtkTetQuality on mixed grids): the
  // summary and histogram read the arrays just filled rather than a copy of every shape.
  std::vector<std::size_t> tetCells;
  bool mixed = false;
  for (std::size_t c = 0; c < count; ++c)
  {
    if (mesh.cells[4 * c] < 0)
    {
      if (!mixed)
        for (std::size_t d = 0; d < c; ++d)
          tetCells.push_back(d); // every cell before the first other one is a tet
      mixed = true;
      continue;
    }
    if (mixed)
      tetCells.push_back(c);
  }
  // Each cell's measures are its own: the two halves of the cells go side by side.
  constexpr std::size_t kMinHalves = 32768;
  forHalves(count,
    wantTwoThreads(0),
    kMinHalves,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t c = begin; c < end; ++c)
      {
        const std::int64_t* ids = mesh.cells + 4 * c;
        if (ids[0] < 0)
          continue;
        const double* x[4];
        double h[4] = { 1, 1, 1, 1 };
        for (int i = 0; i < 4; ++i)
        {
          x[i] = mesh.points + 3 * ids[i];
          if (sizes)
            h[i] = sizes[ids[i]];
        }
        const TetShape shape =
          sizes ? measureTetScaled(x[0], x[1], x[2], x[3], h) : measureTet(x[0], x[1], x[2], x[3]);
        result.quality[c] = shape.quality;
        result.minDihedral[c] = shape.minDihedral;
        result.maxDihedral[c] = shape.maxDihedral;
      }
    });
  const std::size_t tetCount = mixed ? tetCells.size() : count;
  if (tetCount == 0)
  {
    std::ostringstream message;
    message << "the input has no tetrahedra (" << mesh.cellCount
            << " cells, none of type VTK_TETRA)";
    error = message.str();
    return false;
  }
  auto cell = [&](std::size_t n) { return mixed ? tetCells[n] : n; };
  result.summary = summarizeOf(tetCount,
    [&](std::size_t n)
    {
      TetShape s;
      s.quality = result.quality[cell(n)];
      s.minDihedral = result.minDihedral[cell(n)];
      s.maxDihedral = result.maxDihedral[cell(n)];
      return s;
    });
  result.histogram =
    histogramOf(tetCount, binCount, [&](std::size_t n) { return result.quality[cell(n)]; });
  return true;
}

} // namespace tetmesher
