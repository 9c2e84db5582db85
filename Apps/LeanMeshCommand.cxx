// `tetmesher mesh` without VTK: .off, .stl, .vtp, TetGen's, Gmsh's or Medit's surface files in,
// .vtu (or .msh, .mesh, TetGen files) out, the core's whole job (meshSurface, as vtkTetMesher runs
// it) in between; polygons are triangulated as vtkTetMesher does (triangulatePolygon). VTK's ~28
// libraries are loaded (libtetmesherVtk.so) only for what this path leaves to them: other formats,
// a background mesh, cells of fewer than 3 points, triangle strips, a .vtp encoding ReadVtp
// declines, an .stl ReadStl declines, and --with-vtk.
#include "CommandLine.h"
#include "MeshExport.h"
#include "MeshOptions.h"
#include "MeshReport.h"
#include "PolygonTriangulation.h"
#include "SolverSurfaceFiles.h"
#include "SurfaceFiles.h"
#include "SurfaceMeshing.h"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <unistd.h>

namespace tetmesher
{
namespace cli
{

namespace
{
int MeshWithVtk(const MeshOptions& options)
{
  return CallVtkModule("tetmesherMeshWithVtk",
    [&options](void* function)
    {
      using MeshWithVtk = int (*)(const MeshOptions*);
      return reinterpret_cast<MeshWithVtk>(function)(&options);
    });
}

// The surface's triangles for the core, its polygons of more than 3 points triangulated as
// vtkTetMesher does, or false when it has cells that only the VTK path handles (cells of
// fewer than 3 points and strips to refuse, ids beyond 32 bits).
bool Triangles(const SurfaceData& surface,
  std::vector<std::int32_t>& triangles,
  std::vector<std::int64_t>& cellOfTriangle,
  std::int64_t& triangulatedPolygons)
{
  if (surface.stripCells > 0 || surface.PointCount() > std::numeric_limits<std::int32_t>::max() / 2)
    return false;
  const std::int64_t polygons = surface.PolygonCount();
  triangles.clear();
  cellOfTriangle.clear();
  triangles.reserve(static_cast<std::size_t>(3 * polygons));
  cellOfTriangle.reserve(static_cast<std::size_t>(polygons));
  triangulatedPolygons = 0;
  std::vector<std::int32_t> local;
  // Input cell ids of polygons come after the vertices and lines of a vtkPolyData.
  const std::int64_t firstPolyId = surface.vertexCells + surface.lineCells;
  for (std::int64_t p = 0; p < polygons; ++p)
  {
    const auto begin =
      static_cast<std::size_t>(surface.polygonOffsets[static_cast<std::size_t>(p)]);
    const std::int64_t size = surface.polygonOffsets[static_cast<std::size_t>(p + 1)] -
      surface.polygonOffsets[static_cast<std::size_t>(p)];
    if (size < 3)
      return false;
    const std::int64_t* ids = &surface.polygonPoints[begin];
    for (std::int64_t k = 0; k < size; ++k)
      if (ids[k] < std::numeric_limits<std::int32_t>::min() ||
        ids[k] > std::numeric_limits<std::int32_t>::max())
        return false;
    local.clear();
    if (size == 3)
      local = { 0, 1, 2 };
    else
    {
      triangulatePolygon(surface.points.data(), surface.PointCount(), ids, size, local);
      ++triangulatedPolygons;
    }
    for (std::size_t k = 0; k < local.size(); k += 3)
    {
      for (std::size_t c = 0; c < 3; ++c)
        triangles.push_back(static_cast<std::int32_t>(ids[local[k + c]]));
      cellOfTriangle.push_back(firstPolyId + p);
    }
  }
  return true;
}
} // namespace

int RunMesh(int argc, char* argv[])
{
  MeshOptions options;
  options.processStart = std::chrono::steady_clock::now();
  const int usage = ParseMeshOptions(argc, argv, options);
  if (usage >= 0)
    return usage;
  const std::string inExt = LowerExtension(options.input);
  const std::string outExt = LowerExtension(options.output);
  if (options.withVtk || (outExt != ".vtu" && !IsExportExtension(outExt)) ||
    !options.background.empty() ||
    (inExt != ".off" && inExt != ".vtp" && inExt != ".stl" && inExt != ".msh" && inExt != ".mesh" &&
      !IsTetGenSurfaceExtension(inExt)))
    return MeshWithVtk(options);
  return ReportingFileErrors(
    [&]
    {
      StageClock clock(options.processStart);
      RequireReadableFile(options.input);
      SurfaceData surface;
      if (inExt == ".off")
        surface = ReadOff(options.input);
      else if (IsTetGenSurfaceExtension(inExt))
        surface = ReadTetGenSurface(options.input);
      else if (inExt == ".msh")
        surface = ReadGmshSurface(options.input);
      else if (inExt == ".mesh")
        surface = ReadMeditSurface(options.input);
      else if (inExt == ".stl" ? !ReadStl(options.input, surface)
                               : !ReadVtp(options.input, surface))
        return MeshWithVtk(options);
      std::vector<std::int32_t> triangles;
      std::vector<std::int64_t> cellOfTriangle;
      std::int64_t triangulatedPolygons = 0;
      if (!Triangles(surface, triangles, cellOfTriangle, triangulatedPolygons))
        return MeshWithVtk(options);
      WarnAboutIneffectiveOptions(options); // the lean path runs the job: no hand-over now
      clock.Lap("reading");

      SurfaceMeshInput job;
      job.points = surface.points.data();
      job.pointCount = static_cast<std::int32_t>(surface.PointCount());
      job.triangles = triangles.data();
      job.triangleCount = static_cast<std::int32_t>(triangles.size() / 3);
      job.cellOfTriangle = cellOfTriangle.data();
      job.triangleIdsAreNotCellIds =
        surface.vertexCells + surface.lineCells > 0 || triangulatedPolygons > 0;
      job.triangulatedPolygons = static_cast<double>(triangulatedPolygons);
      job.holePoints = surface.holePoints;
      job.holePoints.insert(
        job.holePoints.end(), options.holePoints.begin(), options.holePoints.end());
      job.regionPoints = surface.regionPoints;
      job.regionPoints.insert(
        job.regionPoints.end(), options.regionPoints.begin(), options.regionPoints.end());
      job.regionMaxSizes = surface.regionMaxSizes;
      job.regionMaxSizes.insert(
        job.regionMaxSizes.end(), options.regionMaxSizes.begin(), options.regionMaxSizes.end());
      job.interiorPoints = InteriorPointsOf(options);
      job.sizeArrayName = options.size > 0 ? kConstantSizeArray : options.sizeArray;
      job.readSizeArray = [&](std::vector<double>& sizes)
      {
        if (options.size > 0)
        {
          sizes.assign(static_cast<std::size_t>(surface.PointCount()), options.size);
          return true;
        }
        for (const PointArray& array : surface.pointArrays)
        {
          if (array.name != options.sizeArray)
            continue;
          sizes.resize(static_cast<std::size_t>(surface.PointCount()));
          for (std::size_t p = 0; p < sizes.size(); ++p)
            sizes[p] = array.values[p * static_cast<std::size_t>(array.components)];
          return true;
        }
        return false;
      };
      if (!options.quiet && isatty(STDERR_FILENO))
      {
        job.progress = [](double progress)
        {
          DrawProgress(progress);
          return true;
        };
        DrawProgress(0.0); // as VTK's pipeline does when the filter starts
      }
      const auto start = std::chrono::steady_clock::now();
      const SurfaceMeshOutput mesh = meshSurface(job, SettingsOf(options));
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (!mesh.ok)
      {
        std::fprintf(stderr, "tetmesher: %s: %s\n", options.input.c_str(), mesh.error.c_str());
        return 1;
      }
      clock.Add(mesh.stageTimings);
      if (IsExportExtension(outExt))
      {
        ExportMesh out;
        out.points = mesh.mesh.points.data();
        out.pointCount = static_cast<std::int64_t>(mesh.mesh.points.size() / 3);
        out.cells = mesh.cells.data();
        out.tetCount = static_cast<std::int64_t>(mesh.cells.size() / 4);
        out.regionIds = mesh.mesh.regionIds.empty() ? nullptr : mesh.mesh.regionIds.data();
        out.regionAttribute = mesh.regionAttribute.empty() ? nullptr : mesh.regionAttribute.data();
        out.inputFaceIds = mesh.inputFaceIds.empty() ? nullptr : mesh.inputFaceIds.data();
        WriteExportMesh(out, options.output);
      }
      else
        WriteVtu(mesh, options.output, options.compress);
      clock.Lap("writing");
      MeshSummary summary;
      summary.tetCount = static_cast<long long>(mesh.cells.size() / 4);
      summary.pointCount = static_cast<long long>(mesh.mesh.points.size() / 3);
      summary.field = [&mesh](const char* name)
      {
        for (const auto& [key, value] : mesh.fieldData)
          if (key == name)
            return value;
        return 0.0;
      };
      summary.histogram = mesh.quality.histogram;
      summary.seconds = seconds;
      summary.warnings = mesh.warnings;
      ReportMesh(options, clock, summary);
      return 0;
    });
}

} // namespace cli
} // namespace tetmesher
