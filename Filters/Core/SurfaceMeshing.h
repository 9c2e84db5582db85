// The job of vtkTetMesher without VTK: check the surface, take the size sources, mesh it
// (VolumeMesher.h) and compute every array of the output (tets in VTK_TETRA order,
// RegionId, InputFaceIds, Quality, h, the field data, the histograms). The filter turns the
// result into VTK objects; the command line writes it to a .vtu itself, without loading VTK.
// One implementation for both, so that the two give the same mesh and the same arrays.
#pragma once

#include "QualityOptimization.h"
#include "SurfaceDiagnosis.h"
#include "TetQuality.h"
#include "VolumeMesher.h"

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace tetmesher
{

// vtkTetMesher's properties, with its defaults.
struct SurfaceMeshSettings
{
  bool checkInput = true;
  bool enclosedShellsAreHoles = false;
  bool innerFacets = false; // MesherOptions::innerFacets
  int maximumSteinerPoints = -1;
  bool removeSteinerPoints = true;
  bool refine = true;
  double sizeScale = 1.0;
  double minSize = 0.0;
  double maxSize = 0.0;
  double gradation = 1.5;
  double interpolationPower = 1.0;
  bool optimize = true;
  int optimizationPasses = 3;
  double qualityTarget = 0.35;
  double dihedralTarget = 25.0;
  QualityMeasure measure = QualityMeasure::PaperQ;
  double timeLimit = 0.0;   // seconds; 0: none
  double memoryLimit = 0.0; // MB; 0: the memory available now; < 0: no check
  int numberOfBins = 20;
  // The input diagnosis runs on a second thread beside the boundary mesh from this many
  // triangles (and two CPUs); below, first, on the caller's thread. Starting and joining the
  // thread cost more than it saves on small surfaces: `tetmesher mesh F -o x.vtu -q
  // --boundary-only`, medians of 80 interleaved runs, one thread against two: sphere.off (320
  // triangles) 3.61 / 3.88 ms, blob-closed.off (276) 3.49 / 3.65, part.off (346) 10.31 /
  // 10.45, joint.off (446) 18.20 / 17.98, eight.off (634) 6.51 / 5.76 (2026-12-03).
  int diagnosisBesideMinTriangles = 512;
};

struct SurfaceMeshInput
{
  const double* points = nullptr;
  std::int32_t pointCount = 0;
  const std::int32_t* triangles = nullptr;
  std::int32_t triangleCount = 0;
  // The input cell id of each triangle (InputFaceIds names input cells).
  const std::int64_t* cellOfTriangle = nullptr;
  // The input has vertices, lines or polygons of more than 3 points: the diagnosis then says
  // that its triangle ids are not input cell ids.
  bool triangleIdsAreNotCellIds = false;
  double triangulatedPolygons = 0; // field data TriangulatedPolygonCount
  // TetGen's hole list, 3 doubles per point: the regions containing them are removed.
  std::vector<double> holePoints;
  // TetGen's region list, 4 doubles per point (x, y, z, attribute): the output's
  // mesh.regionAttribute, one value per region (Regions.h).
  std::vector<double> regionPoints;
  // Per region point (may be empty), the largest edge length wanted in its region (<= 0: none).
  std::vector<double> regionMaxSizes;
  // Points to be vertices inside the mesh, 3 doubles per point (VolumeMeshOptions).
  std::vector<double> interiorPoints;
  // The point array of sizes (vtkTetMesher's SizeArrayName), asked for only when refining:
  // fills one value per point, false when the surface has no array of that name.
  std::string sizeArrayName;
  std::function<bool(std::vector<double>& sizes)> readSizeArray;
  // A controlling space (asked for only when refining): sets h(x), or returns an error.
  std::function<std::string(std::function<double(const double*)>& sizeAt)> prepareBackground;
  // Called with the progress in [0, 1]; false stops the job ("meshing was aborted").
  std::function<bool(double)> progress;
};

struct SurfaceMeshOutput
{
  bool ok = false;
  std::string error;
  SurfaceDiagnosis diagnosis; // of the input, when it was checked
  // Its warnings (inconsistent orientation, unused points), one line per kind, with the note
  // on triangle ids when they are not the input's cell ids; empty when there are none.
  std::string warnings;
  VolumeMeshResult mesh;           // points (the first ones the input's), regionIds, vertexSize (h)
  std::vector<std::int64_t> cells; // 4 point ids per tet, VTK_TETRA order
  std::vector<std::int64_t> inputFaceIds; // 4 per tet: the input cell of face i (opposite
                                          // point i of the VTK tet), or -1
  std::vector<double> regionAttribute;    // per tet, its region's attribute (regionPoints);
                                          // empty without region points
  MeshQuality quality;                    // Quality, MinDihedralAngle, MaxDihedralAngle
  // The output's field data in order: the quality summary, then the counts.
  std::vector<std::pair<std::string, double>> fieldData;
  std::vector<std::int64_t> histogramBefore; // Q before optimisation, same bins; may be empty
  // "seconds<TAB>stage" lines, one per stage, after the caller's input conversion.
  std::string stageTimings;
};

SurfaceMeshOutput meshSurface(const SurfaceMeshInput& input, const SurfaceMeshSettings& settings);

} // namespace tetmesher
