// Surfaces in the files of the meshers our users come from, for `tetmesher mesh`: TetGen's
// .smesh, .poly and .face (with its .node), Gmsh's ASCII .msh (formats 2.2 and 4.1), Medit's
// ASCII .mesh (MMG, CGAL, FreeFEM; TetGen reads it too). Read
// without VTK, into the SurfaceData of the other readers, so both paths of the command line
// mesh them alike.
//
// Point ids are the files' points in their order (every point, used by a facet or not, as
// TetGen meshes them); input cell ids count the polygons read, in file order (TetGen: the
// facets, or the polygons of .poly facets; Gmsh and Medit: the triangles and quadrangles). TetGen's
// hole points go to SurfaceData::holePoints (the mesher removes their regions), its region
// list to regionPoints and regionMaxSizes. What the mesh cannot honour is refused by name
// rather than dropped: facets with inner segments or points, polygons nested two deep, Gmsh's
// curved (second-order) elements, binary files.
#pragma once

#include "SurfaceFiles.h"

#include <string>

namespace tetmesher
{
namespace cli
{

// .smesh, .poly, .face (lower case, with the dot).
bool IsTetGenSurfaceExtension(const std::string& lowerExtension);

// The points of a TetGen .node file into surface.points (numbered consecutively from 0 or 1,
// as TetGen numbers them); returns that first number. Throws FileError naming the line.
long ReadTetGenNodeFile(const std::string& nodePath, SurfaceData& surface);

// TetGen's .smesh, .poly or .face, taking the points from NAME.node when the file lists none
// (.face always). The point numbering starts at the first point's number (0 or 1), as
// TetGen's does; its hole and region lists go to SurfaceData's (markers are not used).
// Throws FileError naming the file, line and item.
SurfaceData ReadTetGenSurface(const std::string& path);

// The triangles (element type 2) and quadrangles (type 3) of a Gmsh ASCII .msh file, format
// 2.2 or 4.1, with every node in file order; points, lines and volume elements are skipped.
// Throws FileError naming the file, line and element.
SurfaceData ReadGmshSurface(const std::string& path);

// The triangles and quadrilaterals of a Medit ASCII .mesh file (first order, in file order)
// with every vertex in file order; references, tetrahedra and other sections are not used.
// Throws FileError naming the file, line and element.
SurfaceData ReadMeditSurface(const std::string& path);

} // namespace cli
} // namespace tetmesher
