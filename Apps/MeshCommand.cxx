// `tetmesher mesh` through VTK: vtkTetMesher with VTK's readers and writers. Part of
// libtetmesherVtk.so, which tetmesher loads only for what the lean path (LeanMeshCommand.cxx)
// leaves to VTK: other input and output formats, --background, polygons, --with-vtk.
#include "CommandLine.h"
#include "MeshFiles.h"
#include "MeshOptions.h"
#include "MeshReport.h"
#include "Report.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTetMesher.h"
#include "vtkUnstructuredGrid.h"

#include <chrono>
#include <cstdio>
#include <string>
#include <unistd.h>
#include <vector>

namespace tetmesher
{
namespace cli
{
namespace
{
// A progress bar on stderr, only when it is a terminal.
class ProgressBar : public vtkCommand
{
public:
  static ProgressBar* New() { return new ProgressBar; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    DrawProgress(*static_cast<double*>(data));
  }
};

} // namespace

int RunMeshWithVtk(const MeshOptions& o)
{
  WarnAboutIneffectiveOptions(o);
  return ReportingFileErrors(
    [&o]
    {
      StageClock clock(o.processStart);
      SurfaceData lists; // TetGen's hole and region lists
      vtkSmartPointer<vtkPolyData> surface = ReadSurface(o.input, &lists);
      std::vector<double>& holePoints = lists.holePoints;
      std::vector<double>& regionPoints = lists.regionPoints;
      std::vector<double>& regionMaxSizes = lists.regionMaxSizes;
      clock.Lap("reading");
      vtkNew<vtkTetMesher> mesher;
      std::string sizeArray = o.sizeArray;
      if (o.size > 0)
      {
        // A constant size is a size array like any other.
        vtkNew<vtkDoubleArray> constant;
        constant->SetName(kConstantSizeArray);
        constant->SetNumberOfTuples(surface->GetNumberOfPoints());
        constant->Fill(o.size);
        surface->GetPointData()->AddArray(constant);
        sizeArray = kConstantSizeArray;
      }
      mesher->SetInputData(surface);
      mesher->SetRefine(o.refine && !o.boundaryOnly);
      mesher->SetOptimize(o.optimize && !o.boundaryOnly);
      mesher->SetSizeScale(o.sizeScale);
      mesher->SetMinSize(o.minSize);
      mesher->SetMaxSize(o.maxSize);
      mesher->SetGradation(o.gradation);
      mesher->SetOptimizationPasses(static_cast<int>(o.passes));
      mesher->SetQualityTarget(o.qualityTarget);
      mesher->SetDihedralTarget(o.dihedralTarget);
      mesher->SetTimeLimit(o.timeLimit);
      mesher->SetMemoryLimit(o.memoryLimit);
      if (!sizeArray.empty())
        mesher->SetSizeArrayName(sizeArray.c_str());
      vtkSmartPointer<vtkDataSet> space;
      if (!o.background.empty())
      {
        space = ReadVolumeMesh(o.background);
        mesher->SetInputData(1, space);
        mesher->SetControllingSpaceArrayName(o.backgroundArray.c_str());
      }
      mesher->SetEnclosedShellsAreHoles(o.holes);
      mesher->SetInnerFacets(o.innerFacets);
      holePoints.insert(holePoints.end(), o.holePoints.begin(), o.holePoints.end());
      if (!holePoints.empty())
      {
        vtkNew<vtkPoints> holes;
        holes->SetDataTypeToDouble(); // the lean path's doubles, bit for bit
        for (std::size_t i = 0; i < holePoints.size(); i += 3)
          holes->InsertNextPoint(&holePoints[i]);
        mesher->SetHolePoints(holes);
      }
      regionPoints.insert(regionPoints.end(), o.regionPoints.begin(), o.regionPoints.end());
      regionMaxSizes.insert(regionMaxSizes.end(), o.regionMaxSizes.begin(), o.regionMaxSizes.end());
      for (std::size_t i = 0; i + 3 < regionPoints.size(); i += 4)
        mesher->AddRegionPoint(regionPoints[i],
          regionPoints[i + 1],
          regionPoints[i + 2],
          regionPoints[i + 3],
          i / 4 < regionMaxSizes.size() ? regionMaxSizes[i / 4] : 0.0);
      const std::vector<double> interiorPoints = InteriorPointsOf(o);
      for (std::size_t i = 0; i + 2 < interiorPoints.size(); i += 3)
        mesher->AddInteriorPoint(interiorPoints[i], interiorPoints[i + 1], interiorPoints[i + 2]);
      mesher->SetMaximumSteinerPoints(o.maxSteiner);
      mesher->SetCheckInput(o.check);
      vtkNew<ProgressBar> bar;
      if (!o.quiet && isatty(STDERR_FILENO))
        mesher->AddObserver(vtkCommand::ProgressEvent, bar);
      clock.Lap("filter set-up");
      const auto start = std::chrono::steady_clock::now();
      std::string error = RunFilter(mesher);
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (!error.empty())
      {
        std::fprintf(stderr, "tetmesher: %s: %s\n", o.input.c_str(), error.c_str());
        return 1;
      }
      vtkUnstructuredGrid* mesh = mesher->GetOutput();
      {
        char text[64];
        std::snprintf(text,
          sizeof text,
          "%.4f\tpipeline overhead\n",
          seconds - SumSeconds(mesher->GetStageTimings()));
        clock.Add(mesher->GetStageTimings() + std::string(text));
      }
      WriteVolumeMesh(mesh, o.output, o.compress);
      clock.Lap("writing");
      MeshSummary summary;
      summary.tetCount = static_cast<long long>(mesh->GetNumberOfCells());
      summary.pointCount = static_cast<long long>(mesh->GetNumberOfPoints());
      summary.field = [mesh](const char* name) { return FieldValue(mesh, name); };
      summary.histogram = HistogramCounts(mesher->GetHistogramOutput());
      summary.seconds = seconds;
      summary.warnings = mesher->GetLastWarnings();
      ReportMesh(o, clock, summary);
      return 0;
    });
}

} // namespace cli
} // namespace tetmesher
