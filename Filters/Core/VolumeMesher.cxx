#include "VolumeMesher.h"

#include "GivenPoints.h"
#include "MeshAssembly.h"
#include "ParallelPair.h"
#include "SizeField.h"
#include "TetQuality.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace tetmesher
{
namespace
{
// Maps a stage's progress in [0,1] into [begin, end] of the whole run.
std::function<bool(double)> subProgress(const std::function<bool(double)>& progress,
  double begin,
  double end)
{
  if (!progress)
    return {};
  return [progress, begin, end](double p) { return progress(begin + (end - begin) * p); };
}

// Q (measureTetQuality, VTK's vertex order) of every live tet, in slot order, from the two
// halves of the slots side by side on large meshes (the same values either way).
std::vector<double> liveTetQualities(const TetMesh& mesh)
{
  constexpr TetId kMinHalves = 32768;
  const TetId capacity = mesh.tetCapacity();
  // Reserved, not touched: the first half's vector takes the second's values without a copy.
  std::vector<double> half[2];
  half[0].reserve(static_cast<std::size_t>(capacity));
  half[1].reserve(static_cast<std::size_t>(capacity - capacity / 2));
  splitAt(capacity >= kMinHalves && wantTwoThreads(0),
    capacity / 2,
    capacity,
    [&](int k, TetId first, TetId last)
    {
      for (TetId t = first; t < last; ++t)
        if (!mesh.isDeleted(t))
          // The core's orientation is the reverse of VTK's: vertices 0 and 1 swapped.
          half[k].push_back(measureTetQuality(mesh.point(mesh.vertex(t, 1)),
            mesh.point(mesh.vertex(t, 0)),
            mesh.point(mesh.vertex(t, 2)),
            mesh.point(mesh.vertex(t, 3))));
    });
  half[0].insert(half[0].end(), half[1].begin(), half[1].end());
  return std::move(half[0]);
}
} // namespace

VolumeMeshResult meshVolume(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount,
  const VolumeMeshOptions& options,
  const std::function<bool(double)>& progress)
{
  const auto start = std::chrono::steady_clock::now();
  VolumeMeshResult result;
  auto lapStart = start;
  auto lap = [&](const char* stage)
  {
    const auto now = std::chrono::steady_clock::now();
    result.stageSeconds.emplace_back(stage, std::chrono::duration<double>(now - lapStart).count());
    lapStart = now;
  };
  const bool later = options.refine || options.optimize;
  const std::size_t givenCount = options.interiorPoints.size() / 3;
  const double boundaryShare = later ? 0.4 : 1.0;
  const double refineEnd = options.optimize ? 0.75 : 1.0;

  // A boundary mesh that is the output gets its flat-in-doubles tets flipped away; a mesh
  // refined and optimised next leaves them to the optimiser.
  MesherOptions boundaryOptions = options.boundary;
  boundaryOptions.removeFlatTets = boundaryOptions.removeFlatTets || !later;
  MesherResult boundary = meshSurface(points,
    pointCount,
    triangles,
    triangleCount,
    boundaryOptions,
    subProgress(progress, 0.0, boundaryShare));
  result.steinerPoints = boundary.steinerPoints;
  result.regionCount = boundary.regionCount;
  result.regionAttribute = boundary.regionAttribute;
  {
    const double total =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - lapStart).count();
    const double parts = boundary.delaunaySeconds + boundary.recoverySeconds +
      boundary.regionsSeconds + boundary.flatTetSeconds;
    result.stageSeconds = { { "surface input and checks", std::max(0.0, total - parts) },
      { "Delaunay of the surface points", boundary.delaunaySeconds },
      { "boundary recovery", boundary.recoverySeconds } };
    // The removal of the recovery's Steiner points, when it ran: on CAD parts with many of
    // them, most stay and the attempts can be much of the stage (helix_tube.vtp: 105 points,
    // 5 removed, 0.1 s of 0.17).
    if (boundary.steinerRemovalSeconds > 0)
      result.stageSeconds.emplace_back(
        "(Steiner point removal, within the above)", boundary.steinerRemovalSeconds);
    result.stageSeconds.emplace_back("regions and compaction", boundary.regionsSeconds);
    if (boundaryOptions.removeFlatTets)
      result.stageSeconds.emplace_back("flat tets flipped away", boundary.flatTetSeconds);
    lapStart = std::chrono::steady_clock::now();
  }
  if (!boundary.ok)
  {
    result.error = boundary.error;
    result.boundaryStats = std::move(boundary);
    return result;
  }
  if (!later && givenCount == 0)
  {
    result.points = std::move(boundary.points);
    result.tets = std::move(boundary.tets);
    result.regionIds = std::move(boundary.regionIds);
    result.boundaryFaceTet = std::move(boundary.boundaryFaceTet);
    result.boundaryStats = std::move(boundary);
    result.ok = true;
    result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }

  RegionMesh mesh;
  // The input triangles' faces are locked too: an inner facet (MesherOptions::innerFacets) has
  // one region on both sides, neither boundary nor interface.
  if (!assembleRegionMesh(
        boundary.points, boundary.tets, boundary.regionIds, mesh, boundary.boundaryFaceTet))
  {
    result.error = "internal error: the boundary mesh has a face shared by more than two tets";
    return result;
  }
  lap("mesh assembly");
  // Given interior points (GivenPoints.h): mesh ids from here, output ids from pointCount on.
  const VertexId firstGiven = mesh.mesh.vertexCount();
  if (givenCount > 0)
  {
    const std::string error = insertGivenPoints(mesh,
      options.interiorPoints,
      [pointCount](VertexId v)
      {
        return v < pointCount ? "input point " + std::to_string(v)
                              : std::string("a Steiner point of the boundary mesh");
      });
    if (!error.empty())
    {
      result.error = error;
      return result;
    }
    result.interiorPoints = static_cast<int>(givenCount);
    lap("interior points given");
  }
  // Size field at the input points: given, else the mean boundary edge length there.
  std::vector<double> size = boundaryEdgeSizes(points, pointCount, triangles, triangleCount);
  for (std::size_t i = 0; i < options.inputSizes.size() && i < size.size(); ++i)
  {
    if (options.inputSizes[i] > 0 && std::isfinite(options.inputSizes[i]))
      size[i] = options.inputSizes[i];
  }
  if (options.refine)
  {
    RefinementOptions refinement = options.refinement;
    refinement.regionMaxSize = boundary.regionMaxSize; // the region list's bounds
    result.refinementStats = refineInterior(
      mesh, size, refinement, options.background, subProgress(progress, boundaryShare, refineEnd));
    if (!result.refinementStats.ok)
    {
      result.error = "interior point creation failed: " + result.refinementStats.error;
      return result;
    }
    result.interiorPoints += result.refinementStats.insertedPoints;
    const RefinementResult& r = result.refinementStats;
    lap("refinement");
    // Split the refinement lap into its parts (the rest is the boundary edge sizes).
    const double refinementLap = result.stageSeconds.back().second;
    result.stageSeconds.back() = { "size field and refinement setup",
      std::max(
        0.0, refinementLap - r.latticeCandidateSeconds - r.latticeInsertSeconds - r.splitSeconds) };
    result.stageSeconds.insert(result.stageSeconds.end(),
      { { "lattice candidates", r.latticeCandidateSeconds },
        { "lattice insertion", r.latticeInsertSeconds },
        { "edge splitting", r.splitSeconds } });
  }
  // Measured now: optimisation moves points, so the tets measured later would not be these.
  // The optimiser measures every tet before its first move anyway, and gives their Q from
  // that measure (a scan of its own was 3% of fandisk.off at h = 0.0103).
  if (!options.optimize)
    result.qualityBeforeOptimization = liveTetQualities(mesh.mesh);
  lap("quality before optimisation");
  if (options.optimize)
  {
    // Quality in units of h only when a size field was computed by refinement.
    const std::vector<double>* h = options.refine ? &size : nullptr;
    const std::int64_t budget = options.optimizationPolls < 0 ? -1
                                                              : options.optimizationPolls +
        static_cast<std::int64_t>(
          options.optimizationPollsPerTet * static_cast<double>(mesh.mesh.liveTetCount()));
    std::int64_t polls = 0;
    bool outOfWork = false, aborted = false;
    auto stageProgress = subProgress(progress, refineEnd, 1.0);
    OptimizationOptions optimization = options.optimization;
    optimization.recordQualityBefore = true;
    for (std::size_t i = 0; i < givenCount; ++i)
      optimization.fixedVertices.push_back(firstGiven + static_cast<VertexId>(i));
    result.optimizationStats = optimizeMesh(mesh,
      optimization,
      h,
      [&](double p)
      {
        if (stageProgress && !stageProgress(p))
        {
          aborted = true;
          return false;
        }
        if (budget >= 0 && ++polls > budget)
        {
          outOfWork = true;
          return false;
        }
        return true;
      });
    result.qualityBeforeOptimization = std::move(result.optimizationStats.qualityBefore);
    // Stopped by its work bound, the optimiser leaves a valid mesh: keep it.
    result.optimizationStoppedByBound = outOfWork && !aborted;
    if (!result.optimizationStats.ok && !result.optimizationStoppedByBound)
    {
      result.error = "quality optimisation failed: " + result.optimizationStats.error;
      return result;
    }
    // The optimiser only adds points (vertex insertion), inside the regions.
    result.interiorPoints += result.optimizationStats.insertedVertices;
    lap("optimisation");
  }
  extractRegionMesh(mesh, result.points, result.tets, result.regionIds);
  if (options.refine)
  {
    // Vertices the optimiser inserted have no size yet: the mean of their known neighbours.
    const std::size_t known = size.size(), vertexCount = result.points.size() / 3;
    if (known < vertexCount)
    {
      std::vector<double> sum(vertexCount, 0.0);
      std::vector<int> count(vertexCount, 0);
      for (std::size_t t = 0; t + 3 < result.tets.size(); t += 4)
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j)
          {
            const auto a = static_cast<std::size_t>(result.tets[t + static_cast<std::size_t>(i)]);
            const auto b = static_cast<std::size_t>(result.tets[t + static_cast<std::size_t>(j)]);
            if (a >= known && b < known)
            {
              sum[a] += size[b];
              ++count[a];
            }
          }
      size.resize(vertexCount);
      for (std::size_t v = known; v < vertexCount; ++v)
        size[v] = count[v] > 0 ? sum[v] / count[v] : 0.0;
    }
    result.vertexSize = std::move(size);
  }
  // The given points right after the input points, before the Steiner points.
  if (givenCount > 0 && firstGiven > pointCount)
  {
    const VertexId steiner = firstGiven - pointCount, given = static_cast<VertexId>(givenCount);
    auto newId = [&](VertexId v)
    {
      return v < pointCount      ? v
        : v < firstGiven         ? v + given
        : v < firstGiven + given ? v - steiner
                                 : v;
    };
    for (std::int32_t& v : result.tets)
      v = newId(v);
    auto permute = [&](std::vector<double>& values, std::size_t width)
    {
      if (values.size() < width * static_cast<std::size_t>(firstGiven + given))
        return;
      std::vector<double> moved(values.begin() + width * static_cast<std::size_t>(pointCount),
        values.begin() + width * static_cast<std::size_t>(firstGiven + given));
      for (VertexId v = pointCount; v < firstGiven + given; ++v)
        std::copy_n(moved.begin() + width * static_cast<std::size_t>(v - pointCount),
          width,
          values.begin() + width * static_cast<std::size_t>(newId(v)));
    };
    permute(result.points, 3);
    permute(result.vertexSize, 1);
  }
  result.tetFaceTriangle = tetFaceTriangles(result.tets, triangles, triangleCount);
  result.boundaryFaceTet = firstFaceOfTriangles(result.tetFaceTriangle, triangleCount);
  lap("extraction and boundary faces");
  result.boundaryStats = std::move(boundary);
  result.ok = true;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

} // namespace tetmesher
