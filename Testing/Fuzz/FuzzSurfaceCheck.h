// The property checked on every fuzzer input, shared by the libFuzzer target and the
// regression test: decode the bytes into a surface (FuzzSurfaceInput.h), diagnose it, and
//  - the diagnosis must name only ids that exist and give a non-empty summary;
//  - meshSurface (which runs the same diagnosis) must refuse exactly the surfaces that the
//    diagnosis refuses, inconsistent orientation aside (the mesher ignores it; vtkTetMesher
//    does not);
//  - on a surface the mesher accepts, a successful mesh must keep the input points bit for
//    bit, have positively oriented tets with ids in range, and a tet face equal to every input
//    triangle;
//  - with flag meshInvalidInput, meshSurface(validateInput = false) on refused input must fail
//    or succeed cleanly (no crash, no hang, no sanitizer report).
// Returns an empty string when all hold, otherwise what is wrong.
#pragma once

#include "FuzzSurfaceInput.h"

#include "Mesher.h"
#include "PipelineAsMesherResult.h"
#include "Predicates.h"
#include "SurfaceDiagnosis.h"
#include "VolumeMesher.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace tetmesher
{
namespace fuzz
{

inline std::string checkMesh(const FuzzSurface& s, const MesherResult& r)
{
  const std::int32_t n = s.pointCount();
  if (r.points.size() % 3 != 0 || r.points.size() < s.points.size())
    return "output has fewer points than the input";
  if (std::memcmp(r.points.data(), s.points.data(), s.points.size() * sizeof(double)) != 0)
    return "input points not copied bit for bit";
  const std::int32_t outCount = static_cast<std::int32_t>(r.points.size() / 3);
  if (r.tets.size() % 4 != 0 || r.regionIds.size() != r.tets.size() / 4)
    return "tets/regionIds sizes disagree";
  if (r.steinerPoints != outCount - n)
    return "steinerPoints is not the number of extra points";
  for (std::size_t t = 0; t < r.tets.size() / 4; ++t)
  {
    const std::int32_t* v = &r.tets[4 * t];
    for (int k = 0; k < 4; ++k)
      if (v[k] < 0 || v[k] >= outCount)
        return "tet " + std::to_string(t) + " has a vertex id out of range";
    if (predicates::orient3d(
          &r.points[3 * v[0]], &r.points[3 * v[1]], &r.points[3 * v[2]], &r.points[3 * v[3]]) <= 0)
      return "tet " + std::to_string(t) + " is not positively oriented";
    if (r.regionIds[t] < 0 || r.regionIds[t] >= r.regionCount)
      return "tet " + std::to_string(t) + " has a region id out of range";
  }
  if (r.boundaryFaceTet.size() != static_cast<std::size_t>(s.triangleCount()))
    return "boundaryFaceTet does not have one entry per input triangle";
  for (std::int32_t i = 0; i < s.triangleCount(); ++i)
  {
    const std::int32_t code = r.boundaryFaceTet[i];
    if (code < 0 || static_cast<std::size_t>(code / 4) >= r.tets.size() / 4)
      return "boundaryFaceTet of triangle " + std::to_string(i) + " out of range";
    std::array<std::int32_t, 3> face;
    int k = 0;
    for (int j = 0; j < 4; ++j)
      if (j != code % 4)
        face[k++] = r.tets[4 * (code / 4) + j];
    std::array<std::int32_t, 3> tri = {
      s.triangles[3 * i], s.triangles[3 * i + 1], s.triangles[3 * i + 2]
    };
    std::sort(face.begin(), face.end());
    std::sort(tri.begin(), tri.end());
    if (face != tri)
      return "input triangle " + std::to_string(i) + " is not a face of its boundary tet";
  }
  return {};
}

// Given interior points (GivenPoints.h) on an accepted surface, the boundary mesh alone: the
// centroid of the boundary mesh's largest tet becomes output point n, bit for bit, in a mesh
// that still keeps the surface (or, where rounding puts it outside or on a face, the error
// names interior point 0); input point 0 given again is always an error naming interior point
// 0 (it is a vertex, or outside, or an unused point on the surface left out).
inline std::string checkGivenPoints(const FuzzSurface& s,
  const MesherResult& r,
  const MesherOptions& boundary)
{
  const std::int32_t n = s.pointCount();
  if (r.tets.empty())
    return {};
  std::size_t largest = 0;
  double largestVolume = -1;
  for (std::size_t t = 0; t < r.tets.size() / 4; ++t)
  {
    const double* p[4];
    for (int k = 0; k < 4; ++k)
      p[k] = &r.points[3 * static_cast<std::size_t>(r.tets[4 * t + static_cast<std::size_t>(k)])];
    double e[3][3];
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d)
        e[k][d] = p[k + 1][d] - p[0][d];
    const double volume = std::fabs(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
      e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
      e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]));
    if (volume > largestVolume)
    {
      largestVolume = volume;
      largest = t;
    }
  }
  std::vector<double> centroid(3, 0.0);
  for (int k = 0; k < 4; ++k)
    for (int d = 0; d < 3; ++d)
      centroid[static_cast<std::size_t>(d)] += 0.25 *
        r.points[3 * static_cast<std::size_t>(r.tets[4 * largest + static_cast<std::size_t>(k)]) +
          static_cast<std::size_t>(d)];
  VolumeMeshOptions options;
  options.boundary = boundary;
  options.refine = false;
  options.optimize = false;
  options.interiorPoints = centroid;
  auto namesPoint = [](const std::string& error)
  { return error.rfind("interior point 0 ", 0) == 0; };
  const VolumeMeshResult v =
    meshVolume(s.points.data(), n, s.triangles.data(), s.triangleCount(), options);
  if (!v.ok && !namesPoint(v.error))
    return "given point: " + (v.error.empty() ? std::string("failed without a message") : v.error);
  if (v.ok)
  {
    const std::size_t at = 3 * static_cast<std::size_t>(n);
    if (v.points.size() < at + 3 ||
      std::memcmp(&v.points[at], centroid.data(), 3 * sizeof(double)) != 0 ||
      std::find(v.tets.begin(), v.tets.end(), n) == v.tets.end())
      return "given point: not output point n, bit for bit, in a tet";
    const std::string problem = checkMesh(s, asMesherResult(v, n));
    if (!problem.empty())
      return "given point: " + problem;
  }
  options.interiorPoints.assign(s.points.begin(), s.points.begin() + 3);
  const VolumeMeshResult w =
    meshVolume(s.points.data(), n, s.triangles.data(), s.triangleCount(), options);
  if (w.ok || !namesPoint(w.error))
    return "input point 0 given as an interior point: " +
      (w.ok ? std::string("accepted") : w.error);
  return {};
}

inline std::string runFuzzSurface(const std::uint8_t* data, std::size_t size)
{
  const FuzzSurface s = decodeFuzzSurface(data, size);
  const std::int32_t n = s.pointCount();
  const std::int32_t m = s.triangleCount();
  // The bound the product uses (vtkTetMesher, meshSurface: 1000 records per kind), or a tiny
  // one to exercise truncation. Unbounded, a triangle soup has a quadratic number of
  // intersecting pairs to list (170k records for 2.4k triangles on 90 points: seconds, by
  // design, in a mode no product path uses), which is what the earlier runs' slow inputs were.
  DiagnosisOptions diagnosisOptions;
  diagnosisOptions.maxRecordsPerKind = s.limitRecords ? 3 : 1000;
  diagnosisOptions.innerFacets = s.innerFacets;
  const SurfaceDiagnosis d =
    diagnoseSurface(s.points.data(), n, s.triangles.data(), m, diagnosisOptions);
  if (d.summary().empty())
    return "empty diagnosis summary";
  for (const DefectRecord& record : d.defects)
  {
    for (std::int32_t p : record.pointIds)
      if (p < 0 || p >= n)
        return "diagnosis names point " + std::to_string(p) + " out of range";
    for (std::int32_t t : record.triangleIds)
      if (t < 0 || t >= m)
        return "diagnosis names triangle " + std::to_string(t) + " out of range";
  }
  if (d.ok() && (n == 0 || m == 0))
    return "diagnosis accepts an empty surface";

  MesherOptions options;
  options.enclosedShellsAreHoles = s.enclosedShellsAreHoles;
  options.innerFacets = s.innerFacets;
  // As for a boundary mesh that is the output (--boundary-only): its flat tets flipped away.
  options.removeFlatTets = true;
  const MesherResult r = meshSurface(s.points.data(), n, s.triangles.data(), m, options);
  if (!r.ok && r.error.empty())
    return "meshSurface failed without a message";
  bool blocking = false;
  for (const DefectRecord& record : d.defects)
    if (!isWarning(record.kind))
      blocking = true;
  if (blocking != !d.ok())
    return blocking ? "ok() is true although a defect is an error"
                    : "ok() is false but no defect is an error";
  if (blocking)
  {
    if (r.ok)
      return "meshSurface accepted a surface that the diagnosis refuses: " + d.summary();
    if (s.meshInvalidInput && !(n == 0 || m == 0))
    {
      options.validateInput = false;
      // Recovery on a self-intersecting surface fails only once every missing item has used
      // its Steiner points, which took 3 s in Release (150 s under the fuzzer's ASan) on a
      // fuzzed 1280-triangle sphere. A user of --no-check bounds it with --time-limit; so
      // does this check, and the budget's error is one of the clean endings it accepts.
      options.maxSeconds = kUncheckedSeconds;
      const MesherResult u = meshSurface(s.points.data(), n, s.triangles.data(), m, options);
      if (!u.ok && u.error.empty())
        return "meshSurface(validateInput=false) failed without a message";
    }
    return {};
  }
  if (!r.ok)
    return {};
  std::string problem = checkMesh(s, r);
  if (!problem.empty() || !s.fullPipeline || m > kMaxPipelineTriangles)
    return problem;
  problem = checkGivenPoints(s, r, options);
  if (!problem.empty())
    return problem;
  // The whole pipeline on the accepted surface: it may refuse (a size field beyond the
  // indices), always with a message; a mesh it returns keeps the boundary.
  VolumeMeshOptions volumeOptions;
  volumeOptions.boundary = options;
  volumeOptions.boundary.removeFlatTets = false; // as the pipeline runs it
  volumeOptions.refinement.maxPoints = kMaxPipelinePoints;
  const VolumeMeshResult v = meshVolume(s.points.data(), n, s.triangles.data(), m, volumeOptions);
  if (!v.ok)
    return v.error.empty() ? "meshVolume failed without a message" : std::string();
  problem = checkMesh(s, asMesherResult(v, n));
  return problem.empty() ? problem : "meshVolume: " + problem;
}

} // namespace fuzz
} // namespace tetmesher
