#include "SurfaceMeshing.h"

#include "MemoryBudget.h"
#include "MeshAssembly.h"
#include "ParallelPair.h"
#include "SurfaceQualityBound.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <sstream>
#include <system_error>
#include <thread>

namespace tetmesher
{
namespace
{
// The core orients tets with Shewchuk's orient3d > 0; VTK_TETRA wants the opposite (the
// right-hand normal of points 0,1,2 towards point 3). Swapping points 0 and 1 converts, and
// swaps the faces opposite them.
constexpr int kVtkFromCore[4] = { 1, 0, 2, 3 };

void appendStage(std::string& lines, double seconds, const std::string& stage)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.4f\t", seconds);
  lines += text + stage + "\n";
}
} // namespace

SurfaceMeshOutput meshSurface(const SurfaceMeshInput& input, const SurfaceMeshSettings& settings)
{
  SurfaceMeshOutput out;
  auto lapStart = std::chrono::steady_clock::now();
  auto lap = [&out, &lapStart](const char* stage)
  {
    const auto now = std::chrono::steady_clock::now();
    appendStage(out.stageTimings, std::chrono::duration<double>(now - lapStart).count(), stage);
    lapStart = now;
  };
  // The input diagnosis only reads the input: on a second thread it runs beside the size
  // sources and the whole boundary mesh (turbine: 21 of its 430 ms; fandisk's 31 ms were
  // twice its Delaunay's). Its verdict still comes first: the boundary mesher waits for it
  // before returning, every error path waits for it, and a defect it finds is the error.
  // Once it has found one, meshing stops at its next progress poll (recovery polls every
  // 50 ms) rather than run on.
  const std::string idNote = input.triangleIdsAreNotCellIds
    ? "\n(triangle ids count the triangles of the input's polygons and strips in order; input "
      "cell ids differ when the input has vertices, lines, polygons or strips)"
    : "";
  double diagnosisSeconds = 0;
  std::exception_ptr diagnosisFailure;
  std::atomic<bool> refused{ false }; // the diagnosis found a defect (or failed)
  auto diagnose = [&]
  {
    try
    {
      const auto begin = std::chrono::steady_clock::now();
      DiagnosisOptions diagnosisOptions;
      diagnosisOptions.maxRecordsPerKind = 1000;
      diagnosisOptions.innerFacets = settings.innerFacets;
      out.diagnosis = diagnoseSurface(
        input.points, input.pointCount, input.triangles, input.triangleCount, diagnosisOptions);
      if (!out.diagnosis.ok())
        refused.store(true, std::memory_order_relaxed);
      diagnosisSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    }
    catch (...)
    {
      diagnosisFailure = std::current_exception();
      refused.store(true, std::memory_order_relaxed);
    }
  };
  std::thread diagnosisThread;
  bool diagnosedBeside = false;
  bool diagnosed = !settings.checkInput;
  // The defects that refuse the surface (its warnings stay in out.diagnosis), or "".
  auto diagnosisVerdict = [&]() -> std::string
  {
    if (!diagnosed)
    {
      if (diagnosisThread.joinable())
        diagnosisThread.join();
      else
        diagnose();
      diagnosed = true;
      if (diagnosisFailure)
        std::rethrow_exception(diagnosisFailure);
      // Warnings of a surface that is meshed; a refused one has its defects as the error.
      if (out.diagnosis.ok() && !out.diagnosis.defects.empty())
        out.warnings = out.diagnosis.summary(10) + idNote;
    }
    if (!settings.checkInput || out.diagnosis.ok())
      return "";
    // Open edges and fins are what TetGen's users meet when their facets lie inside the
    // volume: say how to keep such facets (a surface with a hole must still be closed).
    const SurfaceDiagnosis errors = out.diagnosis.errors();
    const bool facetLike =
      errors.count(SurfaceDefect::OpenEdge) > 0 || errors.count(SurfaceDefect::NonManifoldEdge) > 0;
    const std::string facetNote = facetLike
      ? "\n(a surface with a hole must be closed; triangles with the volume on both sides, such "
        "as a sheet or a fin inside it, are kept with --inner-facets, the InnerFacets property)"
      : "";
    return "the input surface cannot be meshed:\n" + errors.summary(10) + idNote + facetNote;
  };
  struct JoinAtExit
  {
    std::thread& thread;
    ~JoinAtExit()
    {
      if (thread.joinable())
        thread.join();
    }
  } joinAtExit{ diagnosisThread };
  auto fail = [&out, &diagnosisVerdict](const std::string& message)
  {
    const std::string defects = diagnosisVerdict();
    out.ok = false;
    out.error = defects.empty() ? message : defects;
    return out;
  };
  auto progress = [&input](double value) { return !input.progress || input.progress(value); };

  if (settings.checkInput)
  {
    if (input.triangleCount >= settings.diagnosisBesideMinTriangles && wantTwoThreads(0))
      try
      {
        diagnosisThread = std::thread(diagnose);
        diagnosedBeside = true;
      }
      catch (const std::system_error&)
      {
      }
    // On one thread, first, as a refused surface needs nothing else.
    if (!diagnosisThread.joinable())
    {
      const std::string defects = diagnosisVerdict();
      if (!defects.empty())
        return fail(defects);
    }
  }
  lap("input diagnosis");
  bool aborted = !progress(0.05);

  // --- Size field sources ---------------------------------------------------------------
  VolumeMeshOptions options;
  if (!input.sizeArrayName.empty() && settings.refine)
  {
    if (!input.readSizeArray || !input.readSizeArray(options.inputSizes))
    {
      return fail("SizeArrayName names point array '" + input.sizeArrayName +
        "', which the input surface does not have");
    }
    for (std::size_t p = 0; p < options.inputSizes.size(); ++p)
    {
      const double h = options.inputSizes[p];
      if (!(h > 0) || !std::isfinite(h))
      {
        std::ostringstream message;
        message << "size array '" << input.sizeArrayName << "' has the invalid value " << h
                << " at point " << p << " (sizes must be finite and > 0)";
        return fail(message.str());
      }
    }
  }
  std::function<double(const double*)> backgroundSize;
  if (settings.refine && input.prepareBackground)
  {
    const std::string error = input.prepareBackground(backgroundSize);
    if (!error.empty())
      return fail("controlling space: " + error);
    if (options.inputSizes.empty())
      options.background = backgroundSize;
  }

  // --- Mesh ------------------------------------------------------------------------------
  // The surface was checked above (or the user chose not to): not twice.
  options.boundary.validateInput = false;
  options.boundary.enclosedShellsAreHoles = settings.enclosedShellsAreHoles;
  options.boundary.innerFacets = settings.innerFacets;
  options.boundary.holePoints = input.holePoints;
  options.boundary.regionPoints = input.regionPoints;
  options.boundary.regionMaxSizes = input.regionMaxSizes;
  options.interiorPoints = input.interiorPoints;
  options.boundary.maxSteinerPoints = settings.maximumSteinerPoints;
  options.boundary.removeSteinerPoints = settings.removeSteinerPoints;
  options.refine = settings.refine;
  options.refinement.size.scale = settings.sizeScale;
  options.refinement.size.minSize = settings.minSize;
  options.refinement.size.maxSize = settings.maxSize;
  options.refinement.size.gradation = settings.gradation;
  options.refinement.size.interpolationPower = settings.interpolationPower;
  options.optimize = settings.optimize && settings.optimizationPasses > 0;
  options.optimization.passes = settings.optimizationPasses;
  options.optimization.qualityTarget = settings.qualityTarget;
  options.optimization.dihedralTarget = settings.dihedralTarget;
  options.optimization.measure = settings.measure;
  options.boundary.maxSeconds = settings.timeLimit;
  options.boundary.inputCheck = diagnosisVerdict;
  // memoryLimit in MB; 0: what the machine has available now; < 0: no check.
  options.refinement.memoryLimitBytes = settings.memoryLimit > 0 ? settings.memoryLimit * 1e6
    : settings.memoryLimit == 0                                  ? availableMemoryBytes()
                                                                 : 0.0;
  options.boundary.memoryLimitBytes = options.refinement.memoryLimitBytes;
  lap("size sources");
  const auto start = std::chrono::steady_clock::now();
  bool outOfTime = false;
  out.mesh = meshVolume(input.points,
    input.pointCount,
    input.triangles,
    input.triangleCount,
    options,
    [&](double fraction)
    {
      if (refused.load(std::memory_order_relaxed))
        return false; // the verdict is the error (fail() below waits for it)
      aborted = aborted || !progress(0.05 + 0.85 * fraction);
      if (settings.timeLimit > 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
          settings.timeLimit)
      {
        outOfTime = true;
        return false;
      }
      return !aborted;
    });
  VolumeMeshResult& result = out.mesh;
  if (aborted)
  {
    return fail("meshing was aborted");
  }
  // The limit ends meshing through the progress callback or through the recovery's own
  // budget, whichever looks first: the same message either way.
  outOfTime = outOfTime ||
    (settings.timeLimit > 0 &&
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
        settings.timeLimit);
  if (outOfTime && !result.ok)
  {
    std::ostringstream message;
    message << "meshing exceeded the time limit of " << settings.timeLimit << " s (" << result.error
            << ")";
    return fail(message.str());
  }
  if (!result.ok)
  {
    return fail(result.error);
  }
  const std::string defects = diagnosisVerdict(); // seen by the boundary mesher already
  if (!defects.empty())
    return fail(defects);
  // What of the region list is not used: later points in a region, sizes without refinement.
  std::string regionNotes = result.boundaryStats.regionNotes;
  if (!settings.refine &&
    std::any_of(
      input.regionMaxSizes.begin(), input.regionMaxSizes.end(), [](double h) { return h > 0; }))
    regionNotes += "the region points' max sizes (volume bounds) are not used: no interior points "
                   "are made (refinement is off)\n";
  if (!regionNotes.empty())
  {
    if (!out.warnings.empty() && out.warnings.back() != '\n')
      out.warnings += '\n';
    out.warnings += regionNotes;
    out.warnings.pop_back(); // as the diagnosis's lines, no newline after the last
  }
  for (const auto& [stage, seconds] : result.stageSeconds)
  {
    appendStage(out.stageTimings, seconds, stage);
  }
  if (diagnosedBeside) // its own time, not a part of the total
    appendStage(out.stageTimings, diagnosisSeconds, "(input diagnosis, beside the above)");
  lapStart = std::chrono::steady_clock::now();

  // --- Output arrays ------------------------------------------------------------------------
  const std::size_t tetCount = result.tets.size() / 4;
  out.cells.resize(4 * tetCount);
  for (std::size_t t = 0; t < tetCount; ++t)
  {
    for (int i = 0; i < 4; ++i)
      out.cells[4 * t + i] = result.tets[4 * t + kVtkFromCore[i]];
  }
  // Every tet face lying on an input triangle (both sides of an interface triangle).
  out.inputFaceIds.assign(4 * tetCount, -1);
  // The volume mesher found them already, unless the boundary mesh is the result.
  if (result.tetFaceTriangle.size() != result.tets.size())
    result.tetFaceTriangle = tetFaceTriangles(result.tets, input.triangles, input.triangleCount);
  const std::vector<std::int32_t>& faceTriangle = result.tetFaceTriangle;
  for (std::size_t t = 0; t < tetCount; ++t)
  {
    for (int f = 0; f < 4; ++f)
    {
      const std::int32_t tri = faceTriangle[4 * t + f];
      if (tri >= 0)
        out.inputFaceIds[4 * t + kVtkFromCore[f]] = input.cellOfTriangle[tri];
    }
  }
  // Each tet's region attribute (TetGen's region list), when region points were given.
  if (!result.regionAttribute.empty())
  {
    out.regionAttribute.resize(tetCount);
    for (std::size_t t = 0; t < tetCount; ++t)
      out.regionAttribute[t] =
        result.regionAttribute[static_cast<std::size_t>(result.regionIds[t])];
  }
  std::vector<std::int32_t>().swap(result.tetFaceTriangle); // used up
  std::vector<std::int32_t>().swap(result.tets);            // out.cells has them
  lap("output conversion");

  std::string qualityError;
  TetMeshView view;
  view.points = result.points.data();
  view.pointCount = static_cast<std::int64_t>(result.points.size() / 3);
  view.cells = out.cells.data();
  view.cellCount = static_cast<std::int64_t>(tetCount);
  if (!measureMesh(view, settings.numberOfBins, out.quality, qualityError))
  {
    return fail("quality of the result: " + qualityError);
  }
  for (const auto& [name, value] : qualitySummaryFields(out.quality.summary))
    out.fieldData.emplace_back(name, value);
  out.fieldData.emplace_back("SteinerPointCount", result.steinerPoints);
  out.fieldData.emplace_back("InteriorPointCount", result.interiorPoints);
  out.fieldData.emplace_back("RegionCount", result.regionCount);
  out.fieldData.emplace_back("TriangulatedPolygonCount", input.triangulatedPolygons);
  out.fieldData.emplace_back("MeshingSeconds", result.seconds);
  // What the surface allows (SurfaceQualityBound.h): no mesh keeping it can have a higher Q
  // min; -1 names no triangle when the bound is 1.
  const SurfaceQualityBound bound =
    surfaceQualityBound(input.points, input.triangles, input.triangleCount);
  out.fieldData.emplace_back("SurfaceQualityBound", bound.bound);
  out.fieldData.emplace_back("SurfaceQualityBoundCellId",
    bound.triangle < 0 ? -1.0 : static_cast<double>(input.cellOfTriangle[bound.triangle]));
  lap("quality arrays");

  // The paper's figure 6 shows the histogram before and after optimisation.
  const std::vector<double>& before = result.qualityBeforeOptimization;
  double minimumBefore = std::numeric_limits<double>::infinity();
  for (double q : before)
    minimumBefore = std::min(minimumBefore, q);
  if (!before.empty())
  {
    out.histogramBefore = qualityHistogram(before, settings.numberOfBins);
    out.fieldData.emplace_back("QualityMinimumBeforeOptimization", minimumBefore);
  }
  std::vector<double>().swap(result.qualityBeforeOptimization); // used up
  lap("histograms");
  progress(1.0);
  out.ok = true;
  return out;
}

} // namespace tetmesher
