#include "MeshOptions.h"

#include "MeshExport.h"
#include "SolverSurfaceFiles.h"
#include "SurfaceFiles.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sys/stat.h>
#include <vector>

namespace tetmesher
{
namespace cli
{
namespace
{
const char* const kMeshUsage = R"(usage: tetmesher mesh SURFACE -o OUT [options]

Tetrahedralizes the closed triangulated surface SURFACE. The boundary of the result is
exactly the input triangles (same points, same coordinates); points 0..n-1 of OUT are the
input points. Interior points follow the size field h (default: the mean length of the
boundary edges at each surface point, interpolated inside), then the worst elements are
improved by flips, edge removal and smoothing.

SURFACE: .stl .obj .ply .vtp .vtk .off, TetGen .smesh .poly .face (points from NAME.node
     when the file lists none; the regions of its hole points are removed, its region
     list gives a RegionAttribute cell array), Gmsh .msh (2.2 or 4.1 ASCII: its
     triangles and quadrangles), Medit .mesh (ASCII: its Triangles and Quadrilaterals);
     input cell ids count the polygons read, in file order
OUT: .vtu or .vtk (VTK), .msh (Gmsh 2.2 ASCII: tets tagged RegionId + 1, or the region
     attribute as physical tag when all are whole numbers from 1; boundary triangles
     input cell id + 1), .node or .ele (TetGen: NAME.node, NAME.ele with the region
     attribute or RegionId, NAME.face with the input cell id + 1 as marker), .mesh
     (Medit ASCII, for MMG: Tetrahedra with reference RegionId + 1, or the region
     attribute when all are whole numbers; Triangles with the input cell id + 1)

options:
  -o, --output FILE     where to write the mesh (required)
  --boundary-only       the boundary mesh alone: no interior points, no optimisation
                        (flips take out most tets whose volume rounds to zero)
  --size H              constant wanted edge length H
  --size-array NAME     wanted edge length from the surface's point array NAME
  --background FILE     controlling space: any VTK dataset with a point array of sizes
  --background-array N  that array's name (default h)
  --size-scale S        multiply every size by S
  --min-size A, --max-size B   clamp the size field
  --gradation G         largest size ratio between neighbours one h apart (default 1.5);
                        next to surface triangles larger than h, sizes also fall from
                        the triangles' own to h at 0.8 of this rate, and next to smaller
                        ones grow from 1.2 times theirs at this rate (1 or less: neither)
  --no-refine           no interior points for a size field: the boundary mesh, then
                        the optimisation, which adds a few points where it needs them
                        (what --boundary-only leaves, with fewer flat and poor tets)
  --no-optimize         skip quality optimisation
  --passes N            optimisation passes (default 3)
  --quality-target Q    optimise tets below this quality (default 0.35)
  --dihedral-target D   then raise the smallest dihedral angles towards D degrees
                        (default 25; 0: no dihedral stage)
  --stats               print the quality summary of the result
  --compress            zlib-compress the arrays of a .vtu (smaller, slower to write)
  --timings             print the wall time of every stage (start-up, reading, the
                        mesher's stages, writing) and the CPU time of all threads
  --with-vtk            run through VTK (vtkTetMesher, VTK's reader and writer) even
                        where the lean path needs no VTK; the same output, slower start
  --holes               enclosed shells are holes instead of regions of their own
  --inner-facets        keep triangles with the volume on both sides (a sheet, a fin on
                        a wall; open edges allowed) as faces inside their region, as
                        TetGen's facets (without: such triangles are input defects)
  --hole X,Y,Z          remove the region containing the point (X,Y,Z), as a hole in
                        TetGen's hole list (repeatable; added to a .smesh/.poly's list)
  --point X,Y,Z         make (X,Y,Z) a vertex strictly inside the mesh, as TetGen's -i
                        list (repeatable): output point N, N+1, ... in the order given,
                        after the N input points; never moved by the optimiser
  --points FILE         the same for every point of a TetGen .node file (TetGen's
                        NAME.a.node for -i), before those of --point
  --region X,Y,Z,A[,H]  give the region containing (X,Y,Z) the attribute A, as TetGen's
                        region list with -A: a RegionAttribute cell array (repeatable;
                        added to a .smesh/.poly's list; other regions: largest A + 1, ...);
                        H > 0 bounds the size there (TetGen's region volume bound)
  --max-steiner N       budget of recovery Steiner points (default 100 + 4 per triangle)
  --time-limit S        stop with an error after S seconds (default: no limit)
  --memory-limit MB     refuse a size field whose mesh is estimated above MB megabytes
                        (default: the memory available; -1: no check)
  --no-check            skip the input surface checks (faster on known-good surfaces)
  -q, --quiet           no progress bar
  -h, --help            this text
)";
// The options by kind: flags set a field, the others take the next argument.
struct Flag
{
  const char* name;
  bool MeshOptions::*field;
  bool value;
};
const Flag kFlags[] = { { "--boundary-only", &MeshOptions::boundaryOnly, true },
  { "--no-refine", &MeshOptions::refine, false },
  { "--no-optimize", &MeshOptions::optimize, false },
  { "--with-vtk", &MeshOptions::withVtk, true },
  { "--stats", &MeshOptions::stats, true },
  { "--timings", &MeshOptions::timings, true },
  { "--compress", &MeshOptions::compress, true },
  { "--holes", &MeshOptions::holes, true },
  { "--inner-facets", &MeshOptions::innerFacets, true },
  { "--no-check", &MeshOptions::check, false },
  { "-q", &MeshOptions::quiet, true },
  { "--quiet", &MeshOptions::quiet, true } };

struct Text
{
  const char* name;
  std::string MeshOptions::*field;
};
const Text kTexts[] = { { "-o", &MeshOptions::output },
  { "--output", &MeshOptions::output },
  { "--size-array", &MeshOptions::sizeArray },
  { "--background", &MeshOptions::background },
  { "--background-array", &MeshOptions::backgroundArray },
  { "--points", &MeshOptions::pointsFile } };

// A number from `low` up; larger than `high` counts as `high`.
struct Number
{
  const char* name;
  double MeshOptions::*field;
  double low, high;
};
constexpr double kNoBound = std::numeric_limits<double>::infinity();
const Number kNumbers[] = { { "--size", &MeshOptions::size, 1e-300, kNoBound },
  { "--size-scale", &MeshOptions::sizeScale, 1e-300, kNoBound },
  { "--min-size", &MeshOptions::minSize, 0, kNoBound },
  { "--max-size", &MeshOptions::maxSize, 0, kNoBound },
  { "--gradation", &MeshOptions::gradation, 0, kNoBound },
  { "--quality-target", &MeshOptions::qualityTarget, 0, 1 },
  { "--passes", &MeshOptions::passes, 0, 100 },
  { "--dihedral-target", &MeshOptions::dihedralTarget, 0, 70 },
  { "--time-limit", &MeshOptions::timeLimit, 0, kNoBound },
  { "--memory-limit", &MeshOptions::memoryLimit, -1, kNoBound } };

template<typename Option, std::size_t N>
const Option* Find(const Option (&options)[N], const std::string& name)
{
  for (const Option& option : options)
    if (name == option.name)
      return &option;
  return nullptr;
}

bool SameFile(const std::string& a, const std::string& b)
{
  struct stat x, y;
  return stat(a.c_str(), &x) == 0 && stat(b.c_str(), &y) == 0 && x.st_dev == y.st_dev &&
    x.st_ino == y.st_ino;
}

// The input file (or the NAME.node a TetGen surface reads) that writing `output` would
// replace ("" when none): TetGen output writes NAME.node, NAME.ele and NAME.face.
std::string OverwrittenInput(const std::string& input, const std::string& output)
{
  const std::string inExt = LowerExtension(input), outExt = LowerExtension(output);
  std::vector<std::string> read{ input }, written{ output };
  if (inExt == ".face" || inExt == ".smesh" || inExt == ".poly")
    read.push_back(input.substr(0, input.size() - inExt.size()) + ".node");
  if (outExt == ".node" || outExt == ".ele")
  {
    const std::string stem = output.substr(0, output.size() - outExt.size());
    written = { stem + ".node", stem + ".ele", stem + ".face" };
  }
  for (const std::string& w : written)
    for (const std::string& r : read)
      if (SameFile(w, r))
        return r;
  return "";
}
} // namespace

int ParseMeshOptions(int argc, char* argv[], MeshOptions& o)
{
  for (int i = 0; i < argc; ++i)
  {
    std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "-h" || arg == "--help")
    {
      std::fputs(kMeshUsage, stdout);
      return 0;
    }
    if (const Flag* flag = Find(kFlags, arg))
      o.*(flag->field) = flag->value;
    else if (const Text* text = hasValue ? Find(kTexts, arg) : nullptr)
      o.*(text->field) = argv[++i];
    else if (const Number* number = hasValue ? Find(kNumbers, arg) : nullptr)
    {
      char* end = nullptr;
      const char* text = argv[++i];
      const double value = std::strtod(text, &end);
      if (*end != '\0' || end == text || !(value >= number->low) || !std::isfinite(value))
      {
        std::fprintf(stderr,
          "tetmesher mesh: %s wants a number >= %g, not '%s'\n",
          arg.c_str(),
          number->low,
          text);
        return 2;
      }
      o.*(number->field) = std::min(value, number->high);
    }
    else if ((arg == "--hole" || arg == "--region" || arg == "--point") && hasValue)
    {
      // --hole X,Y,Z; --point X,Y,Z; --region X,Y,Z,ATTRIBUTE[,MAXSIZE].
      const bool region = arg == "--region";
      const int most = region ? 5 : 3, fewest = region ? 4 : 3;
      const char* text = argv[++i];
      double x[5] = { 0, 0, 0, 0, 0 };
      const char* at = text;
      char* end = nullptr;
      bool ok = true;
      int count = 0;
      while (ok && count < most)
      {
        x[count] = std::strtod(at, &end);
        ok = end != at && std::isfinite(x[count]);
        ++count;
        if (!ok || *end == '\0')
          break;
        ok = *end == ',' && count < most;
        at = end + 1;
      }
      ok = ok && *end == '\0' && count >= fewest && (!region || x[4] >= 0);
      if (!ok)
      {
        if (region)
          std::fprintf(stderr,
            "tetmesher mesh: --region wants X,Y,Z,ATTRIBUTE or X,Y,Z,ATTRIBUTE,MAXSIZE (finite "
            "numbers, MAXSIZE >= 0), not '%s'\n",
            text);
        else
          std::fprintf(stderr,
            "tetmesher mesh: %s wants a point X,Y,Z of three finite numbers, not '%s'\n",
            arg.c_str(),
            text);
        return 2;
      }
      std::vector<double>& list = region ? o.regionPoints
        : arg == "--hole"                ? o.holePoints
                                         : o.interiorPoints;
      list.insert(list.end(), x, x + fewest);
      if (region)
        o.regionMaxSizes.push_back(x[4]);
    }
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
  if (outExt != ".vtu" && outExt != ".vtk" && !IsExportExtension(outExt))
  {
    std::fprintf(stderr,
      "tetmesher mesh: %s: unknown output type '%s' (use .vtu, .vtk, .msh, .mesh, .node or "
      ".ele)\n",
      o.output.c_str(),
      outExt.c_str());
    return 2;
  }
  if (const std::string clash = OverwrittenInput(o.input, o.output); !clash.empty())
  {
    std::fprintf(stderr,
      "tetmesher mesh: %s: writing it would overwrite the input file %s\n",
      o.output.c_str(),
      clash.c_str());
    return 2;
  }
  return -1;
}

void WarnAboutIneffectiveOptions(const MeshOptions& o)
{
  // The size field only places interior points: without them a size option would be silently
  // ignored, so say so.
  if (!o.boundaryOnly && o.refine)
    return;
  const MeshOptions defaults;
  const char* sizeOption = o.size > 0   ? "--size"
    : !o.sizeArray.empty()              ? "--size-array"
    : !o.background.empty()             ? "--background"
    : o.sizeScale != defaults.sizeScale ? "--size-scale"
    : o.minSize > 0                     ? "--min-size"
    : o.maxSize > 0                     ? "--max-size"
    : o.gradation != defaults.gradation ? "--gradation"
                                        : nullptr;
  if (sizeOption)
    std::fprintf(stderr,
      "tetmesher mesh: warning: %s has no effect with %s (no interior points are placed)\n",
      sizeOption,
      o.boundaryOnly ? "--boundary-only" : "--no-refine");
}

std::vector<double> InteriorPointsOf(const MeshOptions& o)
{
  std::vector<double> points;
  if (!o.pointsFile.empty())
  {
    SurfaceData file;
    ReadTetGenNodeFile(o.pointsFile, file);
    points = std::move(file.points);
  }
  points.insert(points.end(), o.interiorPoints.begin(), o.interiorPoints.end());
  return points;
}

SurfaceMeshSettings SettingsOf(const MeshOptions& o)
{
  SurfaceMeshSettings settings;
  settings.checkInput = o.check;
  settings.enclosedShellsAreHoles = o.holes;
  settings.innerFacets = o.innerFacets;
  settings.maximumSteinerPoints = o.maxSteiner;
  settings.refine = o.refine && !o.boundaryOnly;
  settings.sizeScale = o.sizeScale;
  settings.minSize = o.minSize;
  settings.maxSize = o.maxSize;
  settings.gradation = o.gradation;
  settings.optimize = o.optimize && !o.boundaryOnly;
  settings.optimizationPasses = static_cast<int>(o.passes);
  settings.qualityTarget = o.qualityTarget;
  settings.dihedralTarget = o.dihedralTarget;
  settings.timeLimit = o.timeLimit;
  settings.memoryLimit = o.memoryLimit;
  return settings;
}

} // namespace cli
} // namespace tetmesher
