#include "MeshReport.h"

#include "MeshOptions.h"
#include "SurfaceFiles.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <unistd.h>

namespace tetmesher
{
namespace cli
{

void DrawProgress(double progress)
{
  const int filled = static_cast<int>(progress * 30);
  std::fprintf(stderr,
    "\r[%-30s] %3d%%",
    std::string(static_cast<std::size_t>(filled), '#').c_str(),
    static_cast<int>(progress * 100));
  if (progress >= 1.0)
    std::fputs("\r\033[K", stderr);
}

namespace
{
// "IN -> OUT: N tetrahedra, M points (...), R regions, Q min ... mean ..., S s".
void PrintSummaryLine(const std::string& input,
  const std::string& output,
  long long tetCount,
  long long pointCount,
  const FieldLookup& field,
  double seconds)
{
  std::printf("%s -> %s: %lld tetrahedra, %lld points (%d interior, %d Steiner), %d region%s, "
              "Q min %.3f mean %.3f, %.3f s\n",
    input.c_str(),
    output.c_str(),
    tetCount,
    pointCount,
    static_cast<int>(field("InteriorPointCount")),
    static_cast<int>(field("SteinerPointCount")),
    static_cast<int>(field("RegionCount")),
    field("RegionCount") == 1 ? "" : "s",
    field("QualityMinimum"),
    field("QualityMean"),
    seconds);
}
} // namespace

void PrintQualityReport(std::FILE* out,
  const std::string& name,
  long long pointCount,
  const FieldLookup& field,
  bool surfaceBound)
{
  std::fprintf(out,
    "%s: %lld tetrahedra, %lld points\n",
    name.c_str(),
    static_cast<long long>(field("TetrahedronCount")),
    pointCount);
  std::fprintf(out,
    "  quality Q   min %.4f  mean %.4f  1st percentile %.4f\n",
    field("QualityMinimum"),
    field("QualityMean"),
    field("QualityPercentile1"));
  std::fprintf(out,
    "  share       Q < 0.1: %.3f%%  Q < 0.3: %.3f%%\n",
    100.0 * field("QualityShareBelow0.1"),
    100.0 * field("QualityShareBelow0.3"));
  std::fprintf(out,
    "  dihedral    min %.2f deg  max %.2f deg\n",
    field("MinDihedralAngle"),
    field("MaxDihedralAngle"));
  // What the surface allows (SurfaceQualityBound.h), when one of its triangles caps Q below
  // the level the share line counts as poor.
  const double bound = surfaceBound ? field("SurfaceQualityBound") : 1.0;
  if (bound < 0.3)
    std::fprintf(out,
      "  bound       Q min <= %.3g for every mesh that keeps the surface (the shape of input "
      "cell %lld)\n",
      bound,
      static_cast<long long>(field("SurfaceQualityBoundCellId")));
}

void PrintHistogram(std::FILE* out, const std::vector<std::int64_t>& counts)
{
  if (counts.empty())
    return;
  double largest = 1;
  for (std::int64_t n : counts)
    largest = std::max(largest, static_cast<double>(n));
  // The bins of vtkTetQuality's and vtkTetMesher's histogram table (FillHistogramTable).
  const double width = 1.0 / static_cast<double>(counts.size());
  std::fprintf(out, "  histogram of Q\n");
  for (std::size_t i = 0; i < counts.size(); ++i)
  {
    const double n = static_cast<double>(counts[i]);
    const int bar = static_cast<int>(40.0 * n / largest + 0.5);
    std::fprintf(out,
      "  %.2f-%.2f %10lld %s\n",
      width * static_cast<double>(i),
      width * static_cast<double>(i + 1),
      static_cast<long long>(n),
      std::string(static_cast<std::size_t>(bar), '#').c_str());
  }
}

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

void StageClock::Lap(const char* stage)
{
  const auto now = std::chrono::steady_clock::now();
  char text[64];
  std::snprintf(
    text, sizeof text, "%.4f\t", std::chrono::duration<double>(now - this->LapStart).count());
  this->Text += text + std::string(stage) + "\n";
  this->LapStart = now;
}

void StageClock::Add(const std::string& lines)
{
  this->Text += lines;
  this->Restart();
}

void StageClock::Print() const
{
  // Time before main: the dynamic loader and static initialisers.
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
      startup = uptime - std::strtod(c + 1, nullptr) / static_cast<double>(sysconf(_SC_CLK_TCK)) -
        std::chrono::duration<double>(std::chrono::steady_clock::now() - this->ProcessStart)
          .count();
    if (up)
      std::fclose(up);
  }
  const double total = SumSeconds(this->Text.c_str());
  std::printf("timings (wall seconds per stage):\n");
  if (startup >= 0)
    std::printf("  %8.4f  process start-up before main (10 ms resolution)\n", startup);
  for (const char* c = this->Text.c_str(); *c;)
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
  // The CPU time of all the process's threads: over the wall time from main, how many of the
  // machine's CPUs the run kept busy on average (the stages' second threads, the diagnosis).
  const double cpu = static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
  const double wall =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - this->ProcessStart).count();
  if (cpu >= 0 && wall > 0)
    std::printf("  %8.4f  CPU time of all threads (%.2f CPUs busy on average)\n", cpu, cpu / wall);
}

void ReportMesh(const MeshOptions& options, StageClock& clock, const MeshSummary& summary)
{
  // Meshed all the same (the mesh does not depend on them), but said: the user may want
  // to fix the surface for other tools.
  for (std::size_t start = 0; start < summary.warnings.size();)
  {
    std::size_t end = summary.warnings.find('\n', start);
    if (end == std::string::npos)
      end = summary.warnings.size();
    // A note in parentheses (what the triangle ids count) belongs to the warnings above it.
    const bool note = summary.warnings[start] == '(';
    std::fprintf(stderr,
      "tetmesher: %s: %s%.*s\n",
      options.input.c_str(),
      note ? "" : "warning: ",
      static_cast<int>(end - start),
      summary.warnings.c_str() + start);
    start = end + 1;
  }
  PrintSummaryLine(options.input,
    options.output,
    summary.tetCount,
    summary.pointCount,
    summary.field,
    summary.seconds);
  if (options.stats)
  {
    PrintQualityReport(stdout, options.output, summary.pointCount, summary.field, true);
    PrintHistogram(stdout, summary.histogram);
  }
  if (options.timings)
  {
    clock.Lap("summary and statistics");
    clock.Print();
  }
}

int ReportingFileErrors(const std::function<int()>& command)
{
  try
  {
    return command();
  }
  catch (const FileError& e)
  {
    std::fprintf(stderr, "tetmesher: %s\n", e.what());
    return 1;
  }
}

} // namespace cli
} // namespace tetmesher
