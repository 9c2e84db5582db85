// `tetmesher mesh SURFACE -o OUT.vtu`: tetrahedralizes a closed surface with vtkTetMesher.
#include "CommandLine.h"
#include "MeshFiles.h"
#include "Report.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTetMesher.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unistd.h>

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
  --holes               enclosed shells are holes instead of regions of their own
  --max-steiner N       budget of recovery Steiner points (default 100 + 4 per triangle)
  --time-limit S        stop with an error after S seconds (default: no limit)
  --memory-limit MB     refuse a size field whose mesh is estimated above MB megabytes
                        (default: the memory available; -1: no check)
  --no-check            skip the input surface checks (faster on known-good surfaces)
  -q, --quiet           no progress bar
  -h, --help            this text
)";

// A progress bar on stderr, only when it is a terminal.
class ProgressBar : public vtkCommand
{
public:
  static ProgressBar* New() { return new ProgressBar; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    double progress = *static_cast<double*>(data);
    int filled = static_cast<int>(progress * 30);
    std::fprintf(stderr,
      "\r[%-30s] %3d%%",
      std::string(static_cast<std::size_t>(filled), '#').c_str(),
      static_cast<int>(progress * 100));
    if (progress >= 1.0)
      std::fputs("\r\033[K", stderr);
  }
};

// The sum of the first numbers of the lines "seconds<TAB>stage".
double SumSeconds(const char* lines)
{
  double sum = 0;
  for (const char* c = lines; *c;)
  {
    sum += std::strtod(c, nullptr);
    const char* end = std::strchr(c, '\n');
    if (!end)
      break;
    c = end + 1;
  }
  return sum;
}

double Field(vtkUnstructuredGrid* mesh, const char* name)
{
  vtkDataArray* array = mesh->GetFieldData()->GetArray(name);
  return array ? array->GetComponent(0, 0) : 0.0;
}
} // namespace

int RunMesh(int argc, char* argv[])
{
  std::string input, output;
  const auto processStart = std::chrono::steady_clock::now();
  bool stats = false, timings = false, compress = false, holes = false, check = true, quiet = false,
       boundaryOnly = false, optimize = true;
  int maxSteiner = -1, passes = 3;
  double timeLimit = 0, memoryLimit = 0, dihedralTarget = 25, size = 0, sizeScale = 1, minSize = 0,
         maxSize = 0, gradation = 1.5, qualityTarget = 0.35;
  std::string sizeArray, background, backgroundArray = "h";
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
      output = argv[++i];
    else if (arg == "--boundary-only")
      boundaryOnly = true;
    else if (arg == "--no-optimize")
      optimize = false;
    else if (arg == "--size-array" && i + 1 < argc)
      sizeArray = argv[++i];
    else if (arg == "--background" && i + 1 < argc)
      background = argv[++i];
    else if (arg == "--background-array" && i + 1 < argc)
      backgroundArray = argv[++i];
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
        size = value;
      else if (arg == "--size-scale")
        sizeScale = value;
      else if (arg == "--min-size")
        minSize = value;
      else if (arg == "--max-size")
        maxSize = value;
      else if (arg == "--gradation")
        gradation = value;
      else if (arg == "--time-limit")
        timeLimit = value;
      else if (arg == "--memory-limit")
        memoryLimit = value;
      else if (arg == "--dihedral-target")
        dihedralTarget = std::min(value, 70.0);
      else if (arg == "--quality-target")
        qualityTarget = std::min(value, 1.0);
      else
        passes = static_cast<int>(std::min(value, 100.0));
    }
    else if (arg == "--stats")
      stats = true;
    else if (arg == "--timings")
      timings = true;
    else if (arg == "--compress")
      compress = true;
    else if (arg == "--holes")
      holes = true;
    else if (arg == "--no-check")
      check = false;
    else if (arg == "-q" || arg == "--quiet")
      quiet = true;
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
      maxSteiner = static_cast<int>(value);
    }
    else if (!arg.empty() && arg[0] == '-')
    {
      std::fprintf(
        stderr, "tetmesher mesh: unknown or incomplete option '%s'\n\n%s", arg.c_str(), kMeshUsage);
      return 2;
    }
    else if (input.empty())
      input = arg;
    else
    {
      std::fprintf(stderr, "tetmesher mesh: one surface at a time ('%s' is extra)\n", arg.c_str());
      return 2;
    }
  }
  if (input.empty() || output.empty())
  {
    std::fprintf(stderr,
      "tetmesher mesh: %s\n\n%s",
      input.empty() ? "no input surface" : "no output file (-o OUT.vtu)",
      kMeshUsage);
    return 2;
  }
  const std::string outExt = LowerExtension(output);
  if (outExt != ".vtu" && outExt != ".vtk")
  {
    std::fprintf(stderr,
      "tetmesher mesh: %s: unknown output type '%s' (use .vtu or .vtk)\n",
      output.c_str(),
      outExt.c_str());
    return 2;
  }
  try
  {
    std::string timingLines;
    auto lapStart = processStart;
    auto lap = [&](const char* stage)
    {
      const auto now = std::chrono::steady_clock::now();
      char text[64];
      std::snprintf(
        text, sizeof text, "%.4f\t", std::chrono::duration<double>(now - lapStart).count());
      timingLines += text + std::string(stage) + "\n";
      lapStart = now;
    };
    vtkSmartPointer<vtkPolyData> surface = ReadSurface(input);
    lap("reading");
    vtkNew<vtkTetMesher> mesher;
    if (size > 0)
    {
      // A constant size is a size array like any other.
      vtkNew<vtkDoubleArray> constant;
      constant->SetName("tetmesher_constant_size");
      constant->SetNumberOfTuples(surface->GetNumberOfPoints());
      constant->Fill(size);
      surface->GetPointData()->AddArray(constant);
      sizeArray = "tetmesher_constant_size";
    }
    mesher->SetInputData(surface);
    mesher->SetRefine(!boundaryOnly);
    mesher->SetOptimize(optimize && !boundaryOnly);
    mesher->SetSizeScale(sizeScale);
    mesher->SetMinSize(minSize);
    mesher->SetMaxSize(maxSize);
    mesher->SetGradation(gradation);
    mesher->SetOptimizationPasses(passes);
    mesher->SetQualityTarget(qualityTarget);
    mesher->SetDihedralTarget(dihedralTarget);
    mesher->SetTimeLimit(timeLimit);
    mesher->SetMemoryLimit(memoryLimit);
    if (!sizeArray.empty())
      mesher->SetSizeArrayName(sizeArray.c_str());
    vtkSmartPointer<vtkDataSet> space;
    if (!background.empty())
    {
      space = ReadVolumeMesh(background);
      mesher->SetInputData(1, space);
      mesher->SetControllingSpaceArrayName(backgroundArray.c_str());
    }
    mesher->SetEnclosedShellsAreHoles(holes);
    mesher->SetMaximumSteinerPoints(maxSteiner);
    mesher->SetCheckInput(check);
    vtkNew<ProgressBar> bar;
    if (!quiet && isatty(STDERR_FILENO))
      mesher->AddObserver(vtkCommand::ProgressEvent, bar);
    lap("filter set-up");
    auto start = std::chrono::steady_clock::now();
    std::string error = RunFilter(mesher);
    double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!error.empty())
    {
      std::fprintf(stderr, "tetmesher: %s: %s\n", input.c_str(), error.c_str());
      return 1;
    }
    vtkUnstructuredGrid* mesh = mesher->GetOutput();
    {
      timingLines += mesher->GetStageTimings();
      char text[64];
      std::snprintf(text,
        sizeof text,
        "%.4f\tpipeline overhead\n",
        seconds - SumSeconds(mesher->GetStageTimings()));
      timingLines += text;
      lapStart = std::chrono::steady_clock::now();
    }
    WriteVolumeMesh(mesh, output, compress);
    lap("writing");
    std::printf("%s -> %s: %lld tetrahedra, %lld points (%d interior, %d Steiner), %d region%s, "
                "Q min %.3f mean %.3f, %.3f s\n",
      input.c_str(),
      output.c_str(),
      static_cast<long long>(mesh->GetNumberOfCells()),
      static_cast<long long>(mesh->GetNumberOfPoints()),
      static_cast<int>(Field(mesh, "InteriorPointCount")),
      static_cast<int>(Field(mesh, "SteinerPointCount")),
      static_cast<int>(Field(mesh, "RegionCount")),
      Field(mesh, "RegionCount") == 1 ? "" : "s",
      Field(mesh, "QualityMinimum"),
      Field(mesh, "QualityMean"),
      seconds);
    if (stats)
    {
      PrintQualityReport(stdout, output, mesh);
      PrintHistogram(stdout, mesher->GetHistogramOutput());
    }
    if (timings)
    {
      lap("summary and statistics");
      // Time before main: the dynamic loader (VTK's libraries) and static initialisers.
      double startup = -1;
      if (FILE* stat = std::fopen("/proc/self/stat", "r"))
      {
        char buffer[1024];
        const std::size_t n = std::fread(buffer, 1, sizeof buffer - 1, stat);
        std::fclose(stat);
        buffer[n] = '\0';
        // Field 22 (starttime, clock ticks after boot) counts from after the ')' of field 2.
        const char* c = std::strrchr(buffer, ')');
        for (int field = 2; c && field < 22; ++field)
          c = std::strchr(c + 1, ' ');
        double uptime = 0;
        FILE* up = std::fopen("/proc/uptime", "r");
        if (c && up && std::fscanf(up, "%lf", &uptime) == 1)
          startup = uptime -
            std::strtod(c + 1, nullptr) / static_cast<double>(sysconf(_SC_CLK_TCK)) -
            std::chrono::duration<double>(std::chrono::steady_clock::now() - processStart).count();
        if (up)
          std::fclose(up);
      }
      const double total = SumSeconds(timingLines.c_str());
      std::printf("timings (wall seconds per stage):\n");
      if (startup >= 0)
        std::printf("  %8.4f  process start-up before main (10 ms resolution)\n", startup);
      for (const char* c = timingLines.c_str(); *c;)
      {
        const char* tab = std::strchr(c, '\t');
        const char* end = std::strchr(c, '\n');
        if (!tab || !end)
          break;
        std::printf(
          "  %8.4f  %.*s\n", std::strtod(c, nullptr), static_cast<int>(end - tab - 1), tab + 1);
        c = end + 1;
      }
      std::printf("  %8.4f  total after main\n", total);
    }
  }
  catch (const FileError& e)
  {
    std::fprintf(stderr, "tetmesher: %s\n", e.what());
    return 1;
  }
  return 0;
}

} // namespace cli
} // namespace tetmesher
