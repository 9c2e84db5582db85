#include "Mesher.h"

#include "ConstraintRecovery.h"
#include "Delaunay.h"
#include "FlatTetRemoval.h"
#include "MemoryBudget.h"
#include "PerturbationOrder.h"
#include "Regions.h"
#include "SteinerRemoval.h"
#include "SurfaceDiagnosis.h"
#include "SurfaceInput.h"
#include "TetMesh.h"
#include "TriangleIndex.h"
#include "UnusedPoints.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <sstream>

namespace tetmesher
{
namespace
{
double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
// Why input triangle i bounds no kept tet: what lies on its two sides (tetRegion's codes,
// Regions.h), found by a scan of the constrained faces (the error path only).
std::string unkeptTriangleError(const TetMesh& mesh,
  const TriangleIndex& triangleOf,
  std::int32_t i,
  const std::vector<std::int32_t>& tetRegion,
  const std::vector<double>& holePoints)
{
  std::vector<std::int32_t> sides;
  for (TetId t = 0; t < mesh.tetCapacity() && sides.size() < 2; ++t)
  {
    if (mesh.isDeleted(t))
      continue;
    for (int f = 0; f < 4; ++f)
    {
      const int* fv = kFaceVertices[f];
      if (mesh.isConstrained(t, f) &&
        triangleOf.find(mesh.vertex(t, fv[0]), mesh.vertex(t, fv[1]), mesh.vertex(t, fv[2])) == i)
        sides.push_back(
          static_cast<std::size_t>(t) < tetRegion.size() ? tetRegion[t] : kExteriorTet);
    }
  }
  std::sort(sides.begin(), sides.end(), std::greater<>()); // the exterior first
  bool holePoint = false;
  auto describe = [&](std::int32_t code)
  {
    std::ostringstream out;
    if (code == kEnclosedHoleTet)
      out << "an enclosed shell's hole";
    else if (code <= holePointTet(0))
    {
      const std::size_t k = static_cast<std::size_t>(holePointTet(0) - code);
      holePoint = true;
      out << "the region of hole point " << k << " (" << holePoints[3 * k] << ", "
          << holePoints[3 * k + 1] << ", " << holePoints[3 * k + 2] << ")";
    }
    else
      out << "the exterior";
    return out.str();
  };
  std::string message = "input triangle " + std::to_string(i) + " bounds no kept tetrahedron";
  if (sides.size() == 2 && sides[0] == sides[1])
    message += ": " + describe(sides[0]) + " on both sides";
  else if (sides.size() == 2)
    message += ": " + describe(sides[0]) + " on one side, " + describe(sides[1]) + " on the other";
  else
    message += holePoints.empty() ? " (exterior on both sides)"
                                  : " (exterior or a hole point's region on both sides)";
  if (holePoint)
    message += " (TetGen drops such a triangle; the boundary here is the input's exactly: remove "
               "the triangle from the input, or the hole point)";
  return message;
}

} // namespace

MesherResult meshSurface(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount,
  const MesherOptions& options,
  const std::function<bool(double progress)>& progress)
{
  const auto start = std::chrono::steady_clock::now();
  MesherResult result;
  auto report = [&](double fraction) { return !progress || progress(fraction); };

  result.error = checkBoundaryMemoryBudget(pointCount, options.memoryLimitBytes);
  if (!result.error.empty())
    return result;
  SurfaceInput surface;
  result.error =
    buildSurfaceInput(points, pointCount, triangles, triangleCount, surface, options.innerFacets);
  if (!result.error.empty())
    return result;
  if (options.validateInput)
  {
    // Refuse what recovery cannot mesh (self-intersections, coincident points, fins) with a
    // message naming the ids. Warnings (orientation, unused points) do not matter to it.
    // Bounded: a triangle soup can have a quadratic number of intersecting pairs.
    DiagnosisOptions diagnosisOptions;
    diagnosisOptions.maxRecordsPerKind = 1000;
    diagnosisOptions.innerFacets = options.innerFacets;
    SurfaceDiagnosis diagnosis =
      diagnoseSurface(points, pointCount, triangles, triangleCount, diagnosisOptions);
    const SurfaceDiagnosis errors = diagnosis.errors();
    std::string defects = errors.defects.empty() ? std::string() : errors.summary();
    if (!defects.empty())
    {
      result.error = "invalid input surface: " + defects;
      return result;
    }
  }
  if (!report(0.0))
  {
    result.error = "aborted";
    return result;
  }

  // Stage 1: Delaunay of the input points.
  auto stageStart = std::chrono::steady_clock::now();
  TetMesh mesh;
  // Ties of co-circular planar quads broken towards the input's diagonals: fewer edges for
  // recovery to flip in, and fewer Steiner points where flips cannot.
  const PerturbationOrder order = perturbationOrderForSurface(points, surface);
  DelaunayOptions delaunayOptions;
  delaunayOptions.perturbationRank = order.rank.empty() ? nullptr : order.rank.data();
  // Unused points on the surface or equal to another stay out of the mesh (UnusedPoints.h).
  std::vector<std::uint8_t> skip;
  for (const LeftOutPoint& u : unusedPointsLeftOut(points, pointCount, triangles, triangleCount))
  {
    skip.resize(static_cast<std::size_t>(pointCount), 0);
    skip[static_cast<std::size_t>(u.point)] = 1;
  }
  delaunayOptions.skip = skip.empty() ? nullptr : skip.data();
  DelaunayResult delaunay = buildDelaunay(mesh, points, pointCount, delaunayOptions);
  result.delaunaySeconds = secondsSince(stageStart);
  if (!delaunay.ok)
  {
    result.error = "Delaunay tetrahedralization failed: " + delaunay.error;
    return result;
  }
  if (!delaunay.duplicates.empty())
  {
    std::ostringstream error;
    error << "points " << delaunay.duplicateOf[0] << " and " << delaunay.duplicates[0]
          << " coincide (" << delaunay.duplicates.size() << " duplicate points)";
    result.error = error.str();
    return result;
  }
  if (!report(0.2))
  {
    result.error = "aborted";
    return result;
  }

  // Stage 2: boundary recovery.
  stageStart = std::chrono::steady_clock::now();
  RecoveryOptions recoveryOptions;
  recoveryOptions.maxSteinerPoints =
    options.maxSteinerPoints >= 0 ? options.maxSteinerPoints : 100 + 4 * triangleCount;
  recoveryOptions.maxMovesPerItem = options.maxMovesPerItem;
  recoveryOptions.maxSeconds = options.maxSeconds;
  // Unchecked input may intersect itself: name the pair as soon as an item looks stuck.
  recoveryOptions.intersectionProbeAfter = options.validateInput ? 0 : 2;
  RecoveryResult recovery = recoverBoundary(
    mesh, surface, recoveryOptions, [&](double f) { return report(0.2 + 0.7 * f); });
  result.recoverySeconds = secondsSince(stageStart);
  result.flips23 = recovery.flips23;
  result.edgeRemovals = recovery.edgeRemovals;
  result.cavityCones = recovery.cavityCones;
  if (!recovery.ok)
  {
    result.error = recovery.error;
    return result;
  }

  RegionOptions regionOptions;
  regionOptions.firstBoxVertex = delaunay.firstBoxVertex;
  regionOptions.enclosedShellsAreHoles = options.enclosedShellsAreHoles;
  regionOptions.holePoints = options.holePoints;
  regionOptions.regionPoints = options.regionPoints;
  regionOptions.regionMaxSizes = options.regionMaxSizes;
  if (options.removeSteinerPoints && !recovery.steinerVertices.empty())
  {
    const auto removalStart = std::chrono::steady_clock::now();
    // Steiner points outside every region go with the exterior tets (stage 3), and removing
    // them would change no kept tet (no move crosses a constrained face): only the others
    // are removed. Classifying is one flood fill, and the moves keep every region.
    const RegionResult early = classifyRegions(mesh, regionOptions);
    if (!early.error.empty())
    {
      result.error = early.error;
      return result;
    }
    std::vector<char> inside(static_cast<std::size_t>(mesh.vertexCount()), 0);
    for (TetId t = 0; t < mesh.tetCapacity(); ++t)
    {
      if (!mesh.isDeleted(t) && early.tetRegion[t] >= 0)
        for (int i = 0; i < 4; ++i)
          inside[mesh.vertex(t, i)] = 1;
    }
    std::vector<VertexId> kept;
    for (VertexId v : recovery.steinerVertices)
    {
      if (inside[v])
        kept.push_back(v);
    }
    removeSteinerPoints(mesh, kept);
    result.steinerRemovalSeconds = secondsSince(removalStart);
  }
  result.recoverySeconds = secondsSince(stageStart);

  // Stage 3: exterior removal and regions.
  stageStart = std::chrono::steady_clock::now();
  RegionResult regions = classifyRegions(mesh, regionOptions);
  if (!regions.error.empty())
  {
    result.error = regions.error;
    return result;
  }
  result.regionCount = regions.regionCount;
  result.regionAttribute = regions.regionAttribute;
  result.regionMaxSize = regions.regionMaxSize;
  result.regionNotes = regions.regionNotes;
  if (options.removeFlatTets)
  {
    const auto flatStart = std::chrono::steady_clock::now();
    const FlatTetRemovalResult flat = removeFlatTets(mesh, regions.tetRegion);
    result.flatTetsBefore = flat.flatBefore;
    result.flatTetsAfter = flat.flatAfter;
    result.flatTetSeconds = secondsSince(flatStart);
  }

  // Compaction: input points keep their ids, used Steiner points follow in insertion order.
  std::vector<std::int32_t> newId(mesh.vertexCount(), -1);
  for (std::int32_t v = 0; v < pointCount; ++v)
    newId[v] = v;
  std::int32_t nextId = pointCount;
  std::vector<TetId> kept;
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    if (!mesh.isDeleted(t) && regions.tetRegion[t] >= 0)
      kept.push_back(t);
  }
  // One pass marks the used Steiner vertices (box corners are exterior by construction).
  std::vector<char> used(mesh.vertexCount(), 0);
  for (TetId t : kept)
    for (int i = 0; i < 4; ++i)
      used[mesh.vertex(t, i)] = 1;
  for (VertexId v = pointCount; v < mesh.vertexCount(); ++v)
  {
    if (used[v] && (v < delaunay.firstBoxVertex || v >= delaunay.firstBoxVertex + 8))
      newId[v] = nextId++;
  }
  result.steinerPoints = nextId - pointCount;
  result.points.resize(3 * static_cast<std::size_t>(nextId));
  for (VertexId v = 0; v < mesh.vertexCount(); ++v)
  {
    if (newId[v] >= 0)
      for (int k = 0; k < 3; ++k)
        result.points[3 * static_cast<std::size_t>(newId[v]) + k] = mesh.coords[3 * v + k];
  }
  const TriangleIndex triangleOf(surface.triangles);
  result.boundaryFaceTet.assign(triangleCount, -1);
  result.tets.reserve(4 * kept.size());
  result.regionIds.reserve(kept.size());
  for (std::size_t k = 0; k < kept.size(); ++k)
  {
    TetId t = kept[k];
    for (int i = 0; i < 4; ++i)
      result.tets.push_back(newId[mesh.vertex(t, i)]);
    result.regionIds.push_back(regions.tetRegion[t]);
    for (int f = 0; f < 4; ++f)
    {
      if (!mesh.isConstrained(t, f))
        continue;
      const int* fv = kFaceVertices[f];
      const std::int32_t i =
        triangleOf.find(mesh.vertex(t, fv[0]), mesh.vertex(t, fv[1]), mesh.vertex(t, fv[2]));
      if (i >= 0 && result.boundaryFaceTet[i] < 0)
        result.boundaryFaceTet[i] = static_cast<std::int32_t>(4 * k + f);
    }
  }
  result.regionsSeconds = secondsSince(stageStart) - result.flatTetSeconds;
  for (std::int32_t i = 0; i < triangleCount; ++i)
  {
    if (result.boundaryFaceTet[i] < 0)
    {
      // Only possible if a triangle has exterior (or hole) on both sides: a fin or a wall
      // inside a hole, or a hole point's region between the triangle and the exterior.
      result.error =
        unkeptTriangleError(mesh, triangleOf, i, regions.tetRegion, options.holePoints);
      if (options.innerFacets)
        result.error += " (with inner facets allowed, a triangle outside the volume is not "
                        "dropped, and a surface with a hole encloses no volume)";
      result.points.clear();
      result.tets.clear();
      result.regionIds.clear();
      return result;
    }
  }
  // The caller's input check (see MesherOptions::inputCheck) has run beside all of the above.
  if (options.inputCheck)
  {
    result.error = options.inputCheck();
    if (!result.error.empty())
    {
      result.points.clear();
      result.tets.clear();
      result.regionIds.clear();
      return result;
    }
  }
  result.ok = true;
  result.totalSeconds = secondsSince(start);
  report(1.0);
  return result;
}

} // namespace tetmesher
