// The entry point of the VTK-free mesher: a closed triangulated surface in, a tetrahedral mesh
// of its interior out, whose boundary faces are exactly the input triangles (no Steiner point
// on the input surface, coordinates bit-identical, output points 0..n-1 = input points).
// The VTK filter and the CLI wrap exactly this function.
//
// Stages: Delaunay of the input points in a box (Delaunay.h) -> boundary recovery by flips and
// interior Steiner points (ConstraintRecovery.h) -> exterior removal and regions (Regions.h)
// -> compaction (box corners dropped, Steiner points numbered after the input points).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace tetmesher
{

struct MesherOptions
{
  // Nesting depth of a component = number of input surfaces crossed to reach it from the
  // outside. By default every component at depth >= 1 is a region (two nested spheres: the
  // shell and the inner ball, 2 regions). When set, components at even depth (the inner ball)
  // are holes and dropped. Side-by-side materials (shared faces) all have depth 1.
  bool enclosedShellsAreHoles = false;
  // Inner facets, as in TetGen's piecewise linear complexes: triangles with the volume on both
  // sides (open edges, fins on a wall, free sheets) are kept as faces inside a region (two
  // tets, one region). One that lies outside the volume is the run's error, naming it.
  bool innerFacets = false;
  // TetGen's hole list (3 doubles per point): the components containing these points are
  // holes, dropped like the exterior. A point outside the surface or on it is the run's error.
  std::vector<double> holePoints;
  // TetGen's region list (4 doubles per point: x, y, z, attribute; Regions.h): the result's
  // regionAttribute. A point outside the surface, on it or in a hole is the run's error.
  std::vector<double> regionPoints;
  std::vector<double> regionMaxSizes; // per region point, its region's max size (<= 0: none)
  // Budget of recovery Steiner points; -1: 100 + 4 per input triangle. An item still missing
  // after 64 Steiner points near it also ends the run (error naming it).
  int maxSteinerPoints = -1;
  // Bound on flips tried per missing edge/face and per round.
  int maxMovesPerItem = 500;
  // After recovery, take out the Steiner points that flips can remove.
  bool removeSteinerPoints = true;
  // Flip away the tets whose volume rounds to zero or below in doubles (FlatTetRemoval.h),
  // after exterior removal. Off by default: a mesh that is refined and optimised next does not
  // need it (the optimiser lifts them); on for a boundary mesh that is the output.
  bool removeFlatTets = false;
  // Run SurfaceDiagnosis first (self-intersections etc.) and refuse defective input with its
  // message. Without it, such input fails later in recovery, still naming an item.
  bool validateInput = true;
  // Wall-clock budget of boundary recovery in seconds (0: none). When exceeded, meshSurface
  // returns ok = false with an error naming the item being recovered.
  double maxSeconds = 0;
  // Refuse, before building anything, a surface whose boundary mesh is estimated above this
  // many bytes (MemoryBudget.h); <= 0: no memory check. Beyond the 32-bit indices (2^29
  // tets) is always refused.
  double memoryLimitBytes = 0;
  // Called once the boundary mesh is complete, before it is returned; a non-empty answer is
  // the run's error. The caller's input check that runs beside the whole boundary mesh
  // (SurfaceMeshing.cxx) waits here; on the error paths before, the caller waits for it
  // itself, so that a defect it finds is the error even when the Delaunay or recovery fails
  // too (the boundary mesher is fuzzed on unchecked input: it fails with a message or
  // succeeds).
  std::function<std::string()> inputCheck;
};

struct MesherResult
{
  bool ok = false;
  std::string error;                         // names the defect and the input triangle/edge ids
  std::vector<double> points;                // 3 per vertex; the first nInput are the input points
  std::vector<std::int32_t> tets;            // 4 per tet, positively oriented (orient3d > 0)
  std::vector<std::int32_t> regionIds;       // 1 per tet, 0..regionCount-1
  std::vector<std::int32_t> boundaryFaceTet; // per input triangle: 4*t+f of an equal tet face
  int steinerPoints = 0;                     // points in the output beyond the input points
  int regionCount = 0;
  std::vector<double> regionAttribute; // per region, from regionPoints; empty without them
  std::vector<double> regionMaxSize;   // per region, from regionMaxSizes (0: none); may be empty
  std::string regionNotes;             // region points not used (RegionResult::regionNotes)
  int flips23 = 0;
  int edgeRemovals = 0;
  int cavityCones = 0;    // missing edges recovered by refilling their cavity (CavityCone.h)
  int flatTetsBefore = 0; // flat-in-doubles tets before and after removeFlatTets (when on)
  int flatTetsAfter = 0;
  double flatTetSeconds = 0;
  double delaunaySeconds = 0;
  double recoverySeconds = 0;
  double steinerRemovalSeconds = 0; // the part of recoverySeconds that removeSteinerPoints took
  double regionsSeconds = 0;
  double totalSeconds = 0;
};

MesherResult meshSurface(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount,
  const MesherOptions& options = {},
  const std::function<bool(double progress)>& progress = {} /* return false to abort */);

} // namespace tetmesher
