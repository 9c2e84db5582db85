// What `tetmesher` prints, without VTK: the progress bar, the one-line summary of `mesh`,
// the quality report and histogram, and the --timings table. Both the lean path and the VTK
// path (Report.cxx, MeshCommand.cxx) print through these, so their output is the same.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace tetmesher
{
namespace cli
{

// A field data value by name (0 when missing).
using FieldLookup = std::function<double(const char*)>;

// Redraws the progress bar on stderr (the caller checks that stderr is a terminal).
void DrawProgress(double progress);

// "NAME: N tetrahedra, M points" and the quality summary from the field data; with
// surfaceBound (a mesh of ours: the field SurfaceQualityBound is there), also the bound the
// surface puts on Q min when it is below 0.3.
void PrintQualityReport(std::FILE* out,
  const std::string& name,
  long long pointCount,
  const FieldLookup& field,
  bool surfaceBound);

// The histogram of Q, one row per bin of equal width over [0, 1].
void PrintHistogram(std::FILE* out, const std::vector<std::int64_t>& counts);

// Wall time per stage, as lines "seconds<TAB>stage".
class StageClock
{
public:
  explicit StageClock(std::chrono::steady_clock::time_point start)
    : ProcessStart(start)
    , LapStart(start)
  {
  }
  // Ends the stage begun at the last lap (or restart).
  void Lap(const char* stage);
  // Adds lines measured elsewhere, and starts the next stage now.
  void Add(const std::string& lines);
  void Restart() { this->LapStart = std::chrono::steady_clock::now(); }
  const std::string& Lines() const { return this->Text; }
  // Prints the table: process start-up before main, every stage, the total.
  void Print() const;

private:
  std::chrono::steady_clock::time_point ProcessStart, LapStart;
  std::string Text;
};

// The sum of the first numbers of the lines "seconds<TAB>stage".
double SumSeconds(const char* lines);

struct MeshOptions;

// What a `mesh` run reports, whichever path made the mesh.
struct MeshSummary
{
  long long tetCount = 0;
  long long pointCount = 0;
  FieldLookup field; // the mesh's field data
  std::vector<std::int64_t> histogram;
  double seconds = 0; // of the meshing
  // The input check's warnings (inconsistent orientation, unused points), one per line, as
  // the diagnosis words them; empty when there are none or the check was skipped.
  std::string warnings;
};

// The end of a `mesh` run, the same on both paths: the one-line summary, then the quality
// report and histogram (--stats) and the timings (--timings) when asked for.
void ReportMesh(const MeshOptions& options, StageClock& clock, const MeshSummary& summary);

// Runs a command; a FileError it throws becomes "tetmesher: MESSAGE" and exit status 1.
int ReportingFileErrors(const std::function<int()>& command);

} // namespace cli
} // namespace tetmesher
