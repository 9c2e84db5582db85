// `tetmesher mesh` without VTK: .off, .stl or .vtp in, .vtu out, the core's whole job
// (meshSurface, as vtkTetMesher runs it) in between. VTK's ~28 libraries are loaded
// (libtetmesherVtk.so) only for what this path leaves to them: other formats, a background
// mesh, polygons to triangulate, triangle strips, a .vtp encoding ReadVtp declines, an
// .stl ReadStl declines, and --with-vtk.
#include "CommandLine.h"
#include "MeshOptions.h"
#include "MeshReport.h"
#include "SurfaceFiles.h"
#include "SurfaceMeshing.h"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <dlfcn.h>
#include <limits>
#include <unistd.h>

namespace tetmesher
{
namespace cli
{

int CallVtkModule(const char* symbol, const std::function<int(void*)>& call)
{
  static void* module = LoadModule("libtetmesherVtk.so");
  void* function = module ? dlsym(module, symbol) : nullptr;
  if (!function)
  {
    const char* why = dlerror();
    std::fprintf(stderr,
      "tetmesher: cannot load its VTK part (libtetmesherVtk.so: %s)\n",
      why ? why : "missing symbol");
    return 1;
  }
  return call(function);
}

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

// The surface's triangles for the core, or false when it has cells that only the VTK path
// handles (polygons of more than 3 points to triangulate, strips to refuse).
bool Triangles(const SurfaceData& surface,
  std::vector<std::int32_t>& triangles,
  std::vector<std::int64_t>& cellOfTriangle)
{
  if (surface.stripCells > 0 || surface.PointCount() > std::numeric_limits<std::int32_t>::max() / 2)
    return false;
  const std::int64_t polygons = surface.PolygonCount();
  triangles.resize(static_cast<std::size_t>(3 * polygons));
  cellOfTriangle.resize(static_cast<std::size_t>(polygons));
  // Input cell ids of polygons come after the vertices and lines of a vtkPolyData.
  const std::int64_t firstPolyId = surface.vertexCells + surface.lineCells;
  for (std::int64_t p = 0; p < polygons; ++p)
  {
    const auto begin =
      static_cast<std::size_t>(surface.polygonOffsets[static_cast<std::size_t>(p)]);
    if (surface.polygonOffsets[static_cast<std::size_t>(p + 1)] -
        surface.polygonOffsets[static_cast<std::size_t>(p)] !=
      3)
      return false;
    for (std::size_t k = 0; k < 3; ++k)
    {
      const std::int64_t id = surface.polygonPoints[begin + k];
      if (id < std::numeric_limits<std::int32_t>::min() ||
        id > std::numeric_limits<std::int32_t>::max())
        return false;
      triangles[static_cast<std::size_t>(3 * p) + k] = static_cast<std::int32_t>(id);
    }
    cellOfTriangle[static_cast<std::size_t>(p)] = firstPolyId + p;
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
  if (options.withVtk || LowerExtension(options.output) != ".vtu" || !options.background.empty() ||
    (inExt != ".off" && inExt != ".vtp" && inExt != ".stl"))
    return MeshWithVtk(options);
  return ReportingFileErrors(
    [&]
    {
      StageClock clock(options.processStart);
      RequireReadableFile(options.input);
      SurfaceData surface;
      if (inExt == ".off")
        surface = ReadOff(options.input);
      else if (inExt == ".stl" ? !ReadStl(options.input, surface)
                               : !ReadVtp(options.input, surface))
        return MeshWithVtk(options);
      std::vector<std::int32_t> triangles;
      std::vector<std::int64_t> cellOfTriangle;
      if (!Triangles(surface, triangles, cellOfTriangle))
        return MeshWithVtk(options);
      clock.Lap("reading");

      SurfaceMeshInput job;
      job.points = surface.points.data();
      job.pointCount = static_cast<std::int32_t>(surface.PointCount());
      job.triangles = triangles.data();
      job.triangleCount = static_cast<std::int32_t>(triangles.size() / 3);
      job.cellOfTriangle = cellOfTriangle.data();
      job.triangleIdsAreNotCellIds = surface.vertexCells + surface.lineCells > 0;
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
      if (!mesh.diagnosis.defects.empty())
        summary.warnings = mesh.diagnosis.summary(10);
      ReportMesh(options, clock, summary);
      return 0;
    });
}

} // namespace cli
} // namespace tetmesher
