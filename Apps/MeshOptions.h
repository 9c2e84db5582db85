// The options of `tetmesher mesh`, parsed once for both ways of running it: the lean path
// (LeanMeshCommand.cxx, no VTK) and the VTK path (MeshCommand.cxx, in libtetmesherVtk.so).
#pragma once

#include "SurfaceMeshing.h"

#include <chrono>
#include <string>
#include <vector>

namespace tetmesher
{
namespace cli
{

struct MeshOptions
{
  std::chrono::steady_clock::time_point processStart; // when `mesh` began, for --timings
  std::string input, output;
  bool stats = false, timings = false, compress = false, holes = false, check = true, quiet = false,
       boundaryOnly = false, refine = true, optimize = true;
  bool withVtk = false;     // --with-vtk: through vtkTetMesher and VTK's readers and writers
  bool innerFacets = false; // --inner-facets (SurfaceMeshSettings::innerFacets)
  int maxSteiner = -1;
  double passes = 3; // an integer; parsed as the other numbers
  double timeLimit = 0, memoryLimit = 0, dihedralTarget = 25, size = 0, sizeScale = 1, minSize = 0,
         maxSize = 0, gradation = 1.5, qualityTarget = 0.35;
  std::string sizeArray, background, backgroundArray = "h";
  std::vector<double> holePoints;     // --hole X,Y,Z, 3 per point, in the order given
  std::vector<double> interiorPoints; // --point X,Y,Z, 3 per point, in the order given
  std::string pointsFile;             // --points FILE (TetGen .node)
  std::vector<double> regionPoints;   // --region X,Y,Z,A[,H]: X,Y,Z,A, 4 per point, in order
  std::vector<double> regionMaxSizes; // ... and H (0 when not given), 1 per point
};

// Parses the arguments after `mesh`. Returns -1 when the command should run, else the exit
// status (0 after --help, 2 on wrong usage, with the message printed).
int ParseMeshOptions(int argc, char* argv[], MeshOptions& options);
// Warns on stderr about options that the others make ineffective (a size option with
// --boundary-only or --no-refine). Called by the path that runs the job (the lean one, or the
// VTK module's), once it is decided: the static executable hands the VTK path's command line
// to its twin, which parses it again, so a warning printed at parsing would show twice.
void WarnAboutIneffectiveOptions(const MeshOptions& options);

// The points of --points FILE (a TetGen .node file), then those of --point, 3 per point.
// Throws FileError naming the file and line.
std::vector<double> InteriorPointsOf(const MeshOptions& options);

// vtkTetMesher's properties as these options set them (the others keep their defaults).
SurfaceMeshSettings SettingsOf(const MeshOptions& options);

// The name of the constant size array that --size H gives the surface.
constexpr const char* kConstantSizeArray = "tetmesher_constant_size";

} // namespace cli
} // namespace tetmesher
