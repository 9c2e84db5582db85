#include "SolverSurfaceFiles.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

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

// Reserved up to a bound: the counts of a corrupt header must give its error, not bad_alloc.
constexpr long kReserveLimit = 1 << 24;

std::size_t Reserved(long count)
{
  return static_cast<std::size_t>(std::clamp(count, 0L, kReserveLimit));
}

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
  surface.points.reserve(3 * Reserved(count));
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

// NAME.node's points into `surface`; the first point's number.
long ReadTetGenNodeFile(const std::string& nodePath, SurfaceData& surface)
{
  RequireReadableFile(nodePath);
  TokenFile file(nodePath);
  std::istringstream line;
  const long count = ReadTetGenPointHeader(file, line);
  return ReadTetGenPoints(file, line, count, surface);
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
    const long id = corner - first;
    if (id < 0 || id >= surface.PointCount())
      file.Fail(what + ": corner " + std::to_string(corner) + " is not a point (points " +
        std::to_string(first) + " to " + std::to_string(first + surface.PointCount() - 1) + ")");
    out.polygonPoints.push_back(id);
  }
  out.polygonOffsets.push_back(static_cast<std::int64_t>(out.polygonPoints.size()));
}

// Parts 3 and 4 of .smesh and .poly: the hole list (refused unless empty) and the region
// list (noted). Both may be missing at the end of the file.
void ReadHolesAndRegions(TokenFile& file, std::istringstream& line, std::string& notes)
{
  long holes = 0;
  if (!file.NextLine(line))
    return;
  if (!(line >> holes) || holes < 0)
    file.Fail("expected the hole list's count");
  if (holes > 0)
    file.Fail(std::to_string(holes) +
      " hole point(s): tetmesher does not remove regions by hole points (every region the "
      "surface encloses is meshed; 'tetmesher mesh --holes' makes every enclosed shell a hole)");
  long regions = 0;
  if (!file.NextLine(line))
    return;
  if (!(line >> regions) || regions < 0)
    file.Fail("expected the region list's count");
  if (regions > 0)
    notes += "the region list (" + std::to_string(regions) +
      " region(s)) is not used: RegionId numbers the regions in tetmesher's own order\n";
}

} // namespace

SurfaceData ReadTetGenSurface(const std::string& path, std::string& notes)
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
  surface.polygonOffsets.reserve(Reserved(facets) + 1);
  surface.polygonOffsets.push_back(0);
  surface.polygonPoints.reserve(3 * Reserved(facets));
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
        ReadCorners(file, line, corners, first, surface, surface, facet);
      }
      if (holes > 0)
        file.Fail(facet + " has " + std::to_string(holes) +
          " hole(s): facets with holes are not supported (give the facet as polygons "
          "around the hole, e.g. its triangles)");
    }
  }
  if (ext != ".face")
    ReadHolesAndRegions(file, line, notes);
  return surface;
}

SurfaceData ReadGmshSurface(const std::string& path)
{
  RequireReadableFile(path);
  TokenFile file(path);
  std::istringstream line;
  std::string token;
  double version = 0;
  SurfaceData surface;
  std::unordered_map<long, std::int64_t> idOfTag;
  std::vector<long> tags; // of the surface elements' nodes, resolved at the end
  std::vector<long> elementOfPolygon;
  bool nodesRead = false;
  surface.polygonOffsets.push_back(0);

  auto addNode = [&](long tag, double x, double y, double z)
  {
    if (!idOfTag.emplace(tag, surface.PointCount()).second)
      file.Fail("node " + std::to_string(tag) + " is defined twice");
    surface.points.insert(surface.points.end(), { x, y, z });
  };
  // An element of `type` with its node tags next in `line`; element `tag` for messages.
  auto addElement = [&](long tag, long type)
  {
    int corners = 0;
    if (type == 2)
      corners = 3;
    else if (type == 3)
      corners = 4;
    else if (type == 9 || type == 10 || type == 16 || (type >= 20 && type <= 25))
      file.Fail("element " + std::to_string(tag) + " is a curved (second- or higher-order) " +
        "triangle or quadrangle (type " + std::to_string(type) +
        "): save the surface with first-order elements (Gmsh: Mesh.ElementOrder = 1)");
    else
      return; // points, lines, volume elements
    for (int k = 0; k < corners; ++k)
    {
      long node;
      if (!(line >> node))
        file.Fail("element " + std::to_string(tag) + ": expected " + std::to_string(corners) +
          " node tags");
      tags.push_back(node);
    }
    surface.polygonOffsets.push_back(static_cast<std::int64_t>(tags.size()));
    elementOfPolygon.push_back(tag);
  };

  while (file.NextLine(line))
  {
    if (!(line >> token) || token[0] != '$' || token.compare(0, 4, "$End") == 0)
      continue; // the body of a section this reader skips
    if (token == "$MeshFormat")
    {
      int fileType = 0;
      if (!file.NextLine(line) || !(line >> version >> fileType))
        file.Fail("expected 'version file-type data-size' after $MeshFormat");
      if (fileType != 0)
        file.Fail("binary .msh files are not supported; save as ASCII (Gmsh: -format msh2 or "
                  "msh41 with Mesh.Binary=0)");
      if (!(version >= 2 && version < 3) && version != 4.1)
        file.Fail("unsupported .msh version " + std::to_string(version) +
          " (read: 2.2 and 4.1 ASCII; Gmsh: -format msh22 or msh41)");
    }
    else if (token == "$Nodes")
    {
      if (version == 0)
        file.Fail("$Nodes before $MeshFormat");
      if (version < 3)
      {
        long n;
        if (!file.NextLine(line) || !(line >> n) || n < 0)
          file.Fail("expected the node count");
        surface.points.reserve(3 * Reserved(n));
        for (long i = 0; i < n; ++i)
        {
          long tag;
          double x, y, z;
          if (!file.NextLine(line) || !(line >> tag >> x >> y >> z))
            file.Fail("expected node " + std::to_string(i + 1) + " of " + std::to_string(n) +
              " as 'tag x y z'");
          addNode(tag, x, y, z);
        }
      }
      else
      {
        long blocks, n, minTag, maxTag;
        if (!file.NextLine(line) || !(line >> blocks >> n >> minTag >> maxTag) || n < 0)
          file.Fail("expected 'numEntityBlocks numNodes minNodeTag maxNodeTag'");
        surface.points.reserve(3 * Reserved(n));
        for (long b = 0; b < blocks; ++b)
        {
          long dim, entity, parametric, inBlock;
          if (!file.NextLine(line) || !(line >> dim >> entity >> parametric >> inBlock) ||
            inBlock < 0)
            file.Fail("expected a node block's 'entityDim entityTag parametric numNodesInBlock'");
          std::vector<long> blockTags(Reserved(inBlock));
          for (long i = 0; i < inBlock; ++i)
            if (!file.NextLine(line) || !(line >> blockTags[static_cast<std::size_t>(i)]))
              file.Fail("expected a node tag");
          // Parametric coordinates, when present, follow x y z on the line: not read.
          for (long i = 0; i < inBlock; ++i)
          {
            double x, y, z;
            if (!file.NextLine(line) || !(line >> x >> y >> z))
              file.Fail("expected the coordinates 'x y z' of node " +
                std::to_string(blockTags[static_cast<std::size_t>(i)]));
            addNode(blockTags[static_cast<std::size_t>(i)], x, y, z);
          }
        }
      }
      nodesRead = true;
    }
    else if (token == "$Elements")
    {
      if (!nodesRead)
        file.Fail("$Elements before $Nodes");
      if (version < 3)
      {
        long n;
        if (!file.NextLine(line) || !(line >> n) || n < 0)
          file.Fail("expected the element count");
        for (long i = 0; i < n; ++i)
        {
          long tag, type, tagCount;
          if (!file.NextLine(line) || !(line >> tag >> type >> tagCount) || tagCount < 0)
            file.Fail("expected element " + std::to_string(i + 1) + " of " + std::to_string(n) +
              " as 'tag type numTags tags... nodes...'");
          long skip;
          for (long k = 0; k < tagCount; ++k)
            if (!(line >> skip))
              file.Fail("element " + std::to_string(tag) + ": expected " +
                std::to_string(tagCount) + " tags");
          addElement(tag, type);
        }
      }
      else
      {
        long blocks, n, minTag, maxTag;
        if (!file.NextLine(line) || !(line >> blocks >> n >> minTag >> maxTag))
          file.Fail("expected 'numEntityBlocks numElements minElementTag maxElementTag'");
        for (long b = 0; b < blocks; ++b)
        {
          long dim, entity, type, inBlock;
          if (!file.NextLine(line) || !(line >> dim >> entity >> type >> inBlock) || inBlock < 0)
            file.Fail("expected an element block's 'entityDim entityTag elementType "
                      "numElementsInBlock'");
          for (long i = 0; i < inBlock; ++i)
          {
            long tag;
            if (!file.NextLine(line) || !(line >> tag))
              file.Fail("expected an element 'tag nodes...'");
            addElement(tag, type);
          }
        }
      }
    }
  }
  if (version == 0)
    Fail(path, "not a Gmsh .msh file (no $MeshFormat section)");
  if (surface.PolygonCount() == 0)
    Fail(path,
      "no triangles or quadrangles: tetmesher meshes a closed surface (Gmsh: mesh it in 2D, "
      "-2)");
  surface.polygonPoints.reserve(tags.size());
  for (std::size_t i = 0, polygon = 0; i < tags.size(); ++i)
  {
    while (static_cast<std::int64_t>(i) >= surface.polygonOffsets[polygon + 1])
      ++polygon;
    const auto found = idOfTag.find(tags[i]);
    if (found == idOfTag.end())
      Fail(path,
        "element " + std::to_string(elementOfPolygon[polygon]) + " uses undefined node " +
          std::to_string(tags[i]));
    surface.polygonPoints.push_back(found->second);
  }
  return surface;
}

} // namespace cli
} // namespace tetmesher
