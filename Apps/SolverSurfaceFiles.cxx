#include "SolverSurfaceFiles.h"

#include "FacetHoles.h"
#include "GmshFile.h"
#include "MeditFile.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

namespace tetmesher
{
namespace cli
{

bool IsTetGenSurfaceExtension(const std::string& lowerExtension)
{
  return lowerExtension == ".smesh" || lowerExtension == ".poly" || lowerExtension == ".face";
}

namespace
{

// The path of the file with the same name and `extension`.
std::string Sibling(const std::string& path, const std::string& extension)
{
  return path.substr(0, path.size() - LowerExtension(path).size()) + extension;
}

// TetGen's point list: "count 3 [attributes] [markers]", then "number x y z ..." per point,
// numbered consecutively from the first point's number. Returns that first number.
long ReadTetGenPoints(TokenFile& file, std::istringstream& line, long count, SurfaceData& surface)
{
  if (count < 0)
    file.Fail("negative point count " + std::to_string(count));
  surface.points.reserve(3 * ReserveBound(count));
  long first = 0;
  for (long i = 0; i < count; ++i)
  {
    long number;
    double x, y, z;
    if (!file.NextLine(line) || !(line >> number >> x >> y >> z))
      file.Fail("expected point " + std::to_string(i + 1) + " of " + std::to_string(count) +
        " as 'number x y z'");
    if (i == 0)
    {
      if (number != 0 && number != 1)
        file.Fail("the first point is numbered " + std::to_string(number) +
          " (TetGen numbers points from 0 or 1)");
      first = number;
    }
    else if (number != first + i)
      file.Fail("point number " + std::to_string(number) + " where " + std::to_string(first + i) +
        " was expected (points are numbered consecutively)");
    surface.points.insert(surface.points.end(), { x, y, z });
  }
  return first;
}

// The header "count dimension [attributes] [markers]" of a point list; the count.
long ReadTetGenPointHeader(TokenFile& file, std::istringstream& line)
{
  long count, dimension;
  if (!file.NextLine(line) || !(line >> count >> dimension))
    file.Fail("expected the point list's header '<points> 3 <attributes> <markers>'");
  if (dimension != 3)
    file.Fail("dimension " + std::to_string(dimension) + " (a surface in space has 3)");
  return count;
}

// Reads "corners c1 .. cn" of a polygon from `line` (the count already read) as point ids.
void ReadCorners(TokenFile& file,
  std::istringstream& line,
  long corners,
  long first,
  const SurfaceData& surface,
  SurfaceData& out,
  const std::string& what)
{
  for (long k = 0; k < corners; ++k)
  {
    long corner;
    if (!(line >> corner))
      file.Fail(what + ": expected " + std::to_string(corners) + " corners");
    if (corner < first || corner - first >= surface.PointCount())
      file.Fail(what + ": corner " + std::to_string(corner) + " is not a point (points " +
        std::to_string(first) + " to " + std::to_string(first + surface.PointCount() - 1) + ")");
    out.polygonPoints.push_back(corner - first);
  }
  out.polygonOffsets.push_back(static_cast<std::int64_t>(out.polygonPoints.size()));
}

// A .poly facet's hole points ("number x y z" per line, `holes` of them, maybe none) and what
// they leave of its polygons (`polygons`, read apart), added to `surface`.
void AddFacetWithoutHoles(TokenFile& file,
  std::istringstream& line,
  long holes,
  const SurfaceData& polygons,
  SurfaceData& surface,
  const std::string& facet)
{
  std::vector<std::array<double, 3>> points;
  for (long h = 0; h < holes; ++h)
  {
    long number;
    double x, y, z;
    if (!file.NextLine(line) || !(line >> number >> x >> y >> z))
      file.Fail(facet + ": expected hole " + std::to_string(h + 1) + " of " +
        std::to_string(holes) + " as 'number x y z'");
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
      file.Fail(facet + ": hole " + std::to_string(h + 1) + " is not a finite point");
    points.push_back({ x, y, z });
  }
  std::vector<std::vector<std::int64_t>> parts;
  for (std::int64_t p = 0; p < polygons.PolygonCount(); ++p)
    parts.emplace_back(polygons.polygonPoints.begin() + polygons.polygonOffsets[p],
      polygons.polygonPoints.begin() + polygons.polygonOffsets[p + 1]);
  std::string error;
  const bool cut = holes > 0 || PolygonsNested(surface.points, parts);
  const auto kept = cut ? FacetWithoutHoles(surface.points, parts, points, error) : parts;
  if (!error.empty())
    file.Fail(facet + (holes > 0 ? " with holes: " : " with polygons inside a polygon: ") + error);
  for (const auto& polygon : kept)
  {
    surface.polygonPoints.insert(surface.polygonPoints.end(), polygon.begin(), polygon.end());
    surface.polygonOffsets.push_back(static_cast<std::int64_t>(surface.polygonPoints.size()));
  }
}

// Parts 3 and 4 of .smesh and .poly: the hole list (into surface.holePoints) and the region
// list (into surface.regionPoints and regionMaxSizes). Both may be missing at the end.
void ReadHolesAndRegions(TokenFile& file, std::istringstream& line, SurfaceData& surface)
{
  long holes = 0;
  if (!file.NextLine(line))
    return;
  if (!(line >> holes) || holes < 0)
    file.Fail("expected the hole list's count");
  surface.holePoints.reserve(3 * ReserveBound(holes));
  for (long h = 0; h < holes; ++h)
  {
    long number;
    double x, y, z;
    if (!file.NextLine(line) || !(line >> number >> x >> y >> z))
      file.Fail("expected hole point " + std::to_string(h) + " of " + std::to_string(holes) +
        " as 'number x y z'");
    surface.holePoints.insert(surface.holePoints.end(), { x, y, z });
  }
  long regions = 0;
  if (!file.NextLine(line))
    return;
  if (!(line >> regions) || regions < 0)
    file.Fail("expected the region list's count");
  surface.regionPoints.reserve(4 * ReserveBound(regions));
  for (long r = 0; r < regions; ++r)
  {
    long number;
    double x, y, z, attribute, volume = 0;
    if (!file.NextLine(line) || !(line >> number >> x >> y >> z >> attribute))
      file.Fail("expected region " + std::to_string(r) + " of " + std::to_string(regions) +
        " as 'number x y z attribute [volume bound]'");
    // The volume bound is optional; given, it must be a finite number.
    std::string bound;
    if (line >> bound)
    {
      char* end = nullptr;
      volume = std::strtod(bound.c_str(), &end);
      if (end == bound.c_str() || *end != '\0' || !std::isfinite(volume))
        file.Fail("region " + std::to_string(r) + ": the volume bound '" + bound +
          "' is not a finite number");
    }
    surface.regionPoints.insert(surface.regionPoints.end(), { x, y, z, attribute });
    // A volume bound V (> 0; TetGen's -a per region) as the edge of the regular tet of volume
    // V, the size whose tets have that volume: h = (6 sqrt(2) V)^(1/3).
    surface.regionMaxSizes.push_back(volume > 0 ? std::cbrt(6 * std::sqrt(2.0) * volume) : 0.0);
  }
}

} // namespace

long ReadTetGenNodeFile(const std::string& nodePath, SurfaceData& surface)
{
  RequireReadableFile(nodePath);
  TokenFile file(nodePath);
  std::istringstream line;
  const long count = ReadTetGenPointHeader(file, line);
  return ReadTetGenPoints(file, line, count, surface);
}

SurfaceData ReadTetGenSurface(const std::string& path)
{
  const std::string ext = LowerExtension(path);
  RequireReadableFile(path);
  TokenFile file(path);
  std::istringstream line;
  SurfaceData surface;
  long first = 0;
  if (ext == ".face")
    first = ReadTetGenNodeFile(Sibling(path, ".node"), surface);
  else
  {
    const long count = ReadTetGenPointHeader(file, line);
    if (count == 0)
      first = ReadTetGenNodeFile(Sibling(path, ".node"), surface);
    else
      first = ReadTetGenPoints(file, line, count, surface);
  }

  long facets;
  if (!file.NextLine(line) || !(line >> facets) || facets < 0)
    file.Fail(ext == ".face" ? "expected '<faces> <markers>'" : "expected '<facets> <markers>'");
  surface.polygonOffsets.reserve(ReserveBound(facets) + 1);
  surface.polygonOffsets.push_back(0);
  surface.polygonPoints.reserve(3 * ReserveBound(facets));
  for (long f = 0; f < facets; ++f)
  {
    const std::string facet = (ext == ".face" ? "face " : "facet ") + std::to_string(f);
    if (!file.NextLine(line))
      file.Fail("expected " + facet + " (" + std::to_string(facets) + " listed)");
    if (ext == ".face")
    {
      long number;
      line >> number; // its own number; TetGen's .face lists "number a b c [marker]"
      ReadCorners(file, line, 3, first, surface, surface, facet);
    }
    else if (ext == ".smesh")
    {
      long corners;
      if (!(line >> corners) || corners < 3)
        file.Fail(facet + ": expected '<corners> <corner> ...' with 3 or more corners");
      ReadCorners(file, line, corners, first, surface, surface, facet);
    }
    else
    {
      // .poly: "<polygons> [holes] [marker]", the polygons, then the facet's hole points.
      long polygons, holes = 0;
      if (!(line >> polygons) || polygons < 1)
        file.Fail(facet + ": expected '<polygons> [holes] [marker]'");
      line >> holes;
      if (holes < 0)
        file.Fail(facet + ": negative hole count " + std::to_string(holes));
      // One polygon goes straight to the surface; several are read apart, then what the hole
      // points leave of them is added (FacetHoles.h), or, without holes, polygons inside a
      // polygon as the part around them and themselves (TetGen keeps inner polygons as
      // constraints within the facet), and polygons side by side as they are.
      SurfaceData facetPolygons;
      facetPolygons.polygonOffsets.push_back(0);
      SurfaceData& into = holes > 0 || polygons > 1 ? facetPolygons : surface;
      for (long p = 0; p < polygons; ++p)
      {
        long corners;
        if (!file.NextLine(line) || !(line >> corners))
          file.Fail(facet + ": expected polygon " + std::to_string(p + 1) + " of " +
            std::to_string(polygons));
        if (corners < 3)
          file.Fail(facet + ": polygon " + std::to_string(p + 1) + " has " +
            std::to_string(corners) +
            " corner(s): segments and points inside a facet are not supported (give the "
            "facet as polygons of 3 or more corners)");
        ReadCorners(file, line, corners, first, surface, into, facet);
      }
      if (holes > 0 || polygons > 1)
        AddFacetWithoutHoles(file, line, holes, facetPolygons, surface, facet);
    }
  }
  if (ext != ".face")
    ReadHolesAndRegions(file, line, surface);
  return surface;
}

SurfaceData ReadGmshSurface(const std::string& path)
{
  const GmshMesh mesh = ReadGmshMesh(path,
    [](long type, std::string& refusal)
    {
      if (type == 2)
        return 3; // the 3-node triangle
      if (type == 3)
        return 4; // the 4-node quadrangle
      // Gmsh's curved triangles (9, 20-25, 42-46, 52-56) and quadrangles (10, 16, 36-41,
      // 47-51, 57-61): refused, not skipped, or the surface would arrive with holes.
      if (type == 9 || type == 10 || type == 16 || (type >= 20 && type <= 25) ||
        (type >= 36 && type <= 61))
        refusal = "is a curved (second- or higher-order) triangle or quadrangle (type " +
          std::to_string(type) +
          "): save the surface with first-order elements (Gmsh: Mesh.ElementOrder = 1)";
      return 0; // points, lines, volume elements
    });
  if (mesh.ElementCount() == 0)
    Fail(path,
      "no triangles or quadrangles: tetmesher meshes a closed surface (Gmsh: mesh it in 2D, "
      "-2)");
  SurfaceData surface;
  surface.points = mesh.points;
  surface.polygonOffsets = mesh.offsets;
  surface.polygonPoints = mesh.nodes;
  return surface;
}

SurfaceData ReadMeditSurface(const std::string& path)
{
  MeditMesh mesh = ReadMeditMesh(path);
  if (mesh.polygonPoints.empty())
    Fail(path,
      "no Triangles or Quadrilaterals: tetmesher meshes a closed surface (a volume mesh's "
      "boundary is its Triangles section)");
  SurfaceData surface;
  surface.points = std::move(mesh.points);
  surface.polygonOffsets = std::move(mesh.polygonOffsets);
  surface.polygonPoints = std::move(mesh.polygonPoints);
  return surface;
}

} // namespace cli
} // namespace tetmesher
