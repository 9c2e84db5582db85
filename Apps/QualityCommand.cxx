// `tetmesher quality MESH`: reads a tet mesh from any supported format and prints the
// summary that vtkTetQuality computes.
#include "CommandLine.h"
#include "MeshFiles.h"
#include "MeshReport.h"
#include "Report.h"

#include "vtkCommand.h"
#include "vtkDataSet.h"
#include "vtkNew.h"
#include "vtkTable.h"
#include "vtkTetQuality.h"

#include <cstdio>
#include <string>

namespace tetmesher
{
namespace cli
{
namespace
{
const char* const kQualityUsage = R"(usage: tetmesher quality MESH [options]

Prints the quality of the tetrahedra of MESH: Q = 2*sqrt(6)*r_in/l_max (1 = regular,
0 = flat), its minimum, mean, 1st percentile, the share of tets below 0.1 and 0.3, and the
extreme dihedral angles.

MESH: .vtu, .vtk, TetGen NAME.node + NAME.ele (give either), Gmsh ASCII .msh (2.2 or 4.1),
      Medit ASCII .mesh (its Tetrahedra)

options:
  --size-array NAME   measure lengths in units of the point array NAME (size-scaled Q)
  --histogram         also print the histogram of Q (20 bins)
  -h, --help          this text
)";
}

int RunQuality(int argc, char* argv[])
{
  std::string path, sizeArray;
  bool histogram = false;
  for (int i = 0; i < argc; ++i)
  {
    std::string arg = argv[i];
    if (arg == "-h" || arg == "--help")
    {
      std::fputs(kQualityUsage, stdout);
      return 0;
    }
    if (arg == "--histogram")
    {
      histogram = true;
    }
    else if (arg == "--size-array" && i + 1 < argc)
    {
      sizeArray = argv[++i];
    }
    else if (!arg.empty() && arg[0] == '-')
    {
      std::fprintf(
        stderr, "tetmesher quality: unknown option '%s'\n\n%s", arg.c_str(), kQualityUsage);
      return 2;
    }
    else if (path.empty())
    {
      path = arg;
    }
    else
    {
      std::fprintf(stderr, "tetmesher quality: one mesh at a time ('%s' is extra)\n", arg.c_str());
      return 2;
    }
  }
  if (path.empty())
  {
    std::fputs(kQualityUsage, stderr);
    return 2;
  }
  return ReportingFileErrors(
    [&]
    {
      vtkSmartPointer<vtkDataSet> mesh = ReadVolumeMesh(path);
      vtkNew<vtkTetQuality> quality;
      quality->SetInputData(mesh);
      if (!sizeArray.empty())
      {
        quality->SetSizeArrayName(sizeArray.c_str());
      }
      std::string error = RunFilter(quality);
      if (!error.empty())
      {
        std::fprintf(stderr, "tetmesher: %s: %s\n", path.c_str(), error.c_str());
        return 1;
      }
      PrintQualityReport(stdout, path, vtkDataSet::SafeDownCast(quality->GetOutputDataObject(0)));
      if (histogram)
      {
        PrintHistogram(stdout, HistogramCounts(quality->GetHistogramOutput()));
      }
      return 0;
    });
}

} // namespace cli
} // namespace tetmesher
