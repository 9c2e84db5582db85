// The whole pipeline of the paper, as the VTK filter and the CLI run it:
//   boundary mesh (Mesher.h: Delaunay, recovery, regions)
//   -> size field and interior points (SizeField.h, InteriorRefinement.h; section 4.1, 4.4)
//   -> quality optimisation (QualityOptimization.h; section 4.3, 4.5).
// Each later stage keeps the boundary faces (they are constraints) and the regions.
#pragma once

#include "InteriorRefinement.h"
#include "Mesher.h"
#include "QualityOptimization.h"

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace tetmesher
{

// Wall time per stage, in the order the stages ran (name, seconds): cheap (a clock read per
// stage), for `tetmesher mesh --timings` and for profiling.
using StageTimes = std::vector<std::pair<std::string, double>>;

struct VolumeMeshOptions
{
  MesherOptions boundary;
  bool refine = true; // off: the boundary mesh alone (the paper's figure 2)
  RefinementOptions refinement;
  bool optimize = true;
  OptimizationOptions optimization;
  // A bound on the optimiser's work, counted in its progress polls (one per 256 moves tried,
  // and one per pass): at most optimizationPolls + (tets before optimisation) x
  // optimizationPollsPerTet of them, then it stops, keeping the valid, partly improved mesh.
  // Tets it cannot fix (e.g. all four vertices on the surface) would otherwise make it spin
  // on surfaces with poor triangles. Counted in work, not in wall time, so that the same input
  // gives the same mesh on any machine and under any load (a bound of 20x the time of the
  // stages before it stopped CGAL's handle.off at ~14 s, at a different move on each run).
  // None of the Data/ surfaces at their default size reaches 2048 + tets / 64 (alternator
  // comes nearest: 2304 polls of 2822). optimizationPolls < 0: no bound.
  std::int64_t optimizationPolls = 2048;
  double optimizationPollsPerTet = 1.0 / 64;
  // Wanted size h at each input point (raw, before refinement.size scaling); empty or
  // entries <= 0: the mean length of the boundary edges at that point.
  std::vector<double> inputSizes;
  // A controlling space: h(x) anywhere; when set it overrides the interpolation inside.
  std::function<double(const double*)> background;
  // Points to be vertices strictly inside the mesh (3 per point; GivenPoints.h): output ids
  // pointCount .. pointCount + k - 1 in this order, right after the input points (the
  // boundary mesh's Steiner points come after them). They are inserted even when neither
  // refinement nor optimisation runs, and the optimiser never moves them.
  std::vector<double> interiorPoints;
};

struct VolumeMeshResult
{
  bool ok = false;
  std::string error;
  std::vector<double> points;                // first pointCount are the input points, bit-identical
  std::vector<std::int32_t> tets;            // 4 per tet, orient3d > 0 (Shewchuk)
  std::vector<std::int32_t> regionIds;       // per tet
  std::vector<double> vertexSize;            // h used at each vertex (empty if never computed)
  std::vector<std::int32_t> boundaryFaceTet; // per input triangle: 4*t+f of an equal tet face
  // Per tet face 4*t+f: the input triangle it lies on, or -1 (tetFaceTriangles); empty when
  // the boundary mesh is the result.
  std::vector<std::int32_t> tetFaceTriangle;
  // Q (TetQuality.h's measure) of every tet before optimisation, for the before/after histogram.
  std::vector<double> qualityBeforeOptimization;
  int steinerPoints = 0;  // recovery points
  int interiorPoints = 0; // points placed inside: given, by refinement, by the optimiser
  int regionCount = 0;
  std::vector<double> regionAttribute; // per region (MesherResult's); empty without region points
  MesherResult boundaryStats;          // timings and counters of the boundary stage
  RefinementResult refinementStats;
  OptimizationResult optimizationStats;
  bool optimizationStoppedByBound = false; // the work bound above
  double seconds = 0;
  StageTimes stageSeconds;
};

VolumeMeshResult meshVolume(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount,
  const VolumeMeshOptions& options,
  const std::function<bool(double progress)>& progress = {});

} // namespace tetmesher
