#include "MeshOptions.h"

#include "SurfaceFiles.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace tetmesher
{
namespace cli
{
namespace
{
const char* const kMeshUsage = R"(usage: tetmesher mesh SURFACE -o OUT.vtu [options]

Tetrahedralizes the closed triangulated surface SURFACE. The boundary of the result is
exactly the input triangles (same points, same coordinates); points 0..n-1 of OUT are the
input points. Interior points follow the size field h (default: the mean length of the
boundary edges at each surface point, interpolated inside), then the worst elements are
improved by flips, edge removal and smoothing.

SURFACE: .stl .obj .ply .vtp .vtk .off          OUT: .vtu or .vtk

options:
  -o, --output FILE     where to write the mesh (required)
  --boundary-only       the boundary mesh alone: no interior points, no optimisation
  --size H              constant wanted edge length H
  --size-array NAME     wanted edge length from the surface's point array NAME
  --background FILE     controlling space: any VTK dataset with a point array of sizes
  --background-array N  that array's name (default h)
  --size-scale S        multiply every size by S
  --min-size A, --max-size B   clamp the size field
  --gradation G         largest size ratio between neighbours one h apart (default 1.5)
  --no-optimize         skip quality optimisation
  --passes N            optimisation passes (default 3)
  --quality-target Q    optimise tets below this quality (default 0.35)
  --dihedral-target D   then raise the smallest dihedral angles towards D degrees
                        (default 25; 0: no dihedral stage)
  --stats               print the quality summary of the result
  --compress            zlib-compress the arrays of a .vtu (smaller, slower to write)
  --timings             print the wall time of every stage (start-up, reading, the
                        mesher's stages, writing)
  --with-vtk            run through VTK (vtkTetMesher, VTK's reader and writer) even
                        where the lean path needs no VTK; the same output, slower start
  --holes               enclosed shells are holes instead of regions of their own
  --max-steiner N       budget of recovery Steiner points (default 100 + 4 per triangle)
  --time-limit S        stop with an error after S seconds (default: no limit)
  --memory-limit MB     refuse a size field whose mesh is estimated above MB megabytes
                        (default: the memory available; -1: no check)
  --no-check            skip the input surface checks (faster on known-good surfaces)
  -q, --quiet           no progress bar
  -h, --help            this text
)";
} // namespace

int ParseMeshOptions(int argc, char* argv[], MeshOptions& o)
{
  // Parses the number after option argv[i]; false (and a message) when it is not one.
  auto number = [&](int& i, double low, double& value)
  {
    char* end = nullptr;
    const char* text = argv[i + 1];
    value = std::strtod(text, &end);
    if (*end != '\0' || end == text || !(value >= low) || !std::isfinite(value))
    {
      std::fprintf(
        stderr, "tetmesher mesh: %s wants a number >= %g, not '%s'\n", argv[i], low, text);
      return false;
    }
    ++i;
    return true;
  };
  for (int i = 0; i < argc; ++i)
  {
    std::string arg = argv[i];
    if (arg == "-h" || arg == "--help")
    {
      std::fputs(kMeshUsage, stdout);
      return 0;
    }
    if ((arg == "-o" || arg == "--output") && i + 1 < argc)
      o.output = argv[++i];
    else if (arg == "--boundary-only")
      o.boundaryOnly = true;
    else if (arg == "--no-optimize")
      o.optimize = false;
    else if (arg == "--size-array" && i + 1 < argc)
      o.sizeArray = argv[++i];
    else if (arg == "--background" && i + 1 < argc)
      o.background = argv[++i];
    else if (arg == "--background-array" && i + 1 < argc)
      o.backgroundArray = argv[++i];
    else if (i + 1 < argc &&
      (arg == "--size" || arg == "--size-scale" || arg == "--min-size" || arg == "--max-size" ||
        arg == "--gradation" || arg == "--quality-target" || arg == "--passes" ||
        arg == "--dihedral-target" || arg == "--time-limit" || arg == "--memory-limit"))
    {
      double value = 0;
      const double low = arg == "--size" || arg == "--size-scale" ? 1e-300
        : arg == "--memory-limit"                                 ? -1.0
                                                                  : 0.0;
      if (!number(i, low, value))
        return 2;
      if (arg == "--size")
        o.size = value;
      else if (arg == "--size-scale")
        o.sizeScale = value;
      else if (arg == "--min-size")
        o.minSize = value;
      else if (arg == "--max-size")
        o.maxSize = value;
      else if (arg == "--gradation")
        o.gradation = value;
      else if (arg == "--time-limit")
        o.timeLimit = value;
      else if (arg == "--memory-limit")
        o.memoryLimit = value;
      else if (arg == "--dihedral-target")
        o.dihedralTarget = std::min(value, 70.0);
      else if (arg == "--quality-target")
        o.qualityTarget = std::min(value, 1.0);
      else
        o.passes = static_cast<int>(std::min(value, 100.0));
    }
    else if (arg == "--with-vtk")
      o.withVtk = true;
    else if (arg == "--stats")
      o.stats = true;
    else if (arg == "--timings")
      o.timings = true;
    else if (arg == "--compress")
      o.compress = true;
    else if (arg == "--holes")
      o.holes = true;
    else if (arg == "--no-check")
      o.check = false;
    else if (arg == "-q" || arg == "--quiet")
      o.quiet = true;
    else if (arg == "--max-steiner" && i + 1 < argc)
    {
      char* end = nullptr;
      long value = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || value < -1 || value > 1000000000)
      {
        std::fprintf(
          stderr, "tetmesher mesh: --max-steiner wants an integer >= -1, not '%s'\n", argv[i]);
        return 2;
      }
      o.maxSteiner = static_cast<int>(value);
    }
    else if (!arg.empty() && arg[0] == '-')
    {
      std::fprintf(
        stderr, "tetmesher mesh: unknown or incomplete option '%s'\n\n%s", arg.c_str(), kMeshUsage);
      return 2;
    }
    else if (o.input.empty())
      o.input = arg;
    else
    {
      std::fprintf(stderr, "tetmesher mesh: one surface at a time ('%s' is extra)\n", arg.c_str());
      return 2;
    }
  }
  if (o.input.empty() || o.output.empty())
  {
    std::fprintf(stderr,
      "tetmesher mesh: %s\n\n%s",
      o.input.empty() ? "no input surface" : "no output file (-o OUT.vtu)",
      kMeshUsage);
    return 2;
  }
  const std::string outExt = LowerExtension(o.output);
  if (outExt != ".vtu" && outExt != ".vtk")
  {
    std::fprintf(stderr,
      "tetmesher mesh: %s: unknown output type '%s' (use .vtu or .vtk)\n",
      o.output.c_str(),
      outExt.c_str());
    return 2;
  }
  return -1;
}

SurfaceMeshSettings SettingsOf(const MeshOptions& o)
{
  SurfaceMeshSettings settings;
  settings.checkInput = o.check;
  settings.enclosedShellsAreHoles = o.holes;
  settings.maximumSteinerPoints = o.maxSteiner;
  settings.refine = !o.boundaryOnly;
  settings.sizeScale = o.sizeScale;
  settings.minSize = o.minSize;
  settings.maxSize = o.maxSize;
  settings.gradation = o.gradation;
  settings.optimize = o.optimize && !o.boundaryOnly;
  settings.optimizationPasses = o.passes;
  settings.qualityTarget = o.qualityTarget;
  settings.dihedralTarget = o.dihedralTarget;
  settings.timeLimit = o.timeLimit;
  settings.memoryLimit = o.memoryLimit;
  return settings;
}

} // namespace cli
} // namespace tetmesher
