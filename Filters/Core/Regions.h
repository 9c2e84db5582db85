// Exterior removal and region marking (George-Hecht-Saltel 1990, section 3.6): once every
// input face is a constrained face, flood fill over tet adjacency that does not cross one
// splits the box into components. Components with a box corner are exterior. The others are
// numbered; their nesting depth (how many input surfaces separate them from the exterior)
// tells enclosed shells apart, which become holes on request.
#pragma once

#include "TetMesh.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tetmesher
{

struct RegionOptions
{
  VertexId firstBoxVertex = -1; // box corners are firstBoxVertex .. firstBoxVertex+7
  // Components at even depth >= 2 (inside a region, e.g. the inner ball of two nested
  // spheres) are holes instead of regions of their own.
  bool enclosedShellsAreHoles = false;
  // TetGen's hole list: the components containing these points (3 doubles each) are holes.
  // A point outside the surface, or on it (decided exactly), is an error naming it.
  std::vector<double> holePoints;
  // TetGen's region list (4 doubles per point: x, y, z, attribute): each region takes the
  // attribute of the first point in it; the others take the largest given attribute + 1, + 2,
  // ... in region order (as TetGen's -A). A point outside the surface, on it or in a hole is
  // an error naming it.
  std::vector<double> regionPoints;
  // Per region point (empty: none), the largest edge length wanted in its region (TetGen's
  // volume bound per region, as the edge of the regular tet of that volume); <= 0: none.
  std::vector<double> regionMaxSizes;
};

constexpr std::int32_t kExteriorTet = -1;
constexpr std::int32_t kEnclosedHoleTet = -2;
constexpr std::int32_t holePointTet(std::int32_t k)
{
  return -3 - k;
}

struct RegionResult
{
  // Per tet slot: the region id (>= 0), or why the tet is not kept: kExteriorTet (the
  // exterior, or a free slot), kEnclosedHoleTet (an enclosed shell made a hole), or
  // holePointTet(k) (the region of hole point k).
  std::vector<std::int32_t> tetRegion;
  int regionCount = 0;
  // Per region, its attribute (RegionOptions::regionPoints); empty without region points.
  std::vector<double> regionAttribute;
  // Per region, the first region point's max size there (0: none); empty without any.
  std::vector<double> regionMaxSize;
  // A line per later region point whose attribute or size differs from its region's first
  // point's (it is not used: the first wins), for the warnings.
  std::string regionNotes;
  std::string error; // a hole or region point outside the surface or on it (or a region point
                     // in a hole); tetRegion is then empty
};

RegionResult classifyRegions(const TetMesh& mesh, const RegionOptions& options);

} // namespace tetmesher
