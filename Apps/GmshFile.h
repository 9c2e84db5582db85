// Gmsh's ASCII .msh files, formats 2.2 and 4.1, without VTK: the nodes and the elements of
// the types a caller keeps. One reader for `tetmesher quality` (tetrahedra) and `tetmesher
// mesh` (triangles and quadrangles).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace tetmesher
{
namespace cli
{

struct GmshMesh
{
  std::vector<double> points; // 3 per node, every node in file order
  // The kept elements in file order: element i has the point ids
  // nodes[offsets[i], offsets[i + 1]), Gmsh type types[i] and tag tags[i].
  std::vector<std::int64_t> offsets{ 0 };
  std::vector<std::int64_t> nodes;
  std::vector<long> types;
  std::vector<long> tags;

  std::size_t ElementCount() const { return types.size(); }
};

// How many of an element's nodes to keep (its corners), by its Gmsh type: 0 skips the
// element; a non-empty `refusal` fails the file with "element TAG " + refusal.
using GmshElementFilter = std::function<int(long type, std::string& refusal)>;

// Throws FileError naming the file, the line and the defect (binary files, versions other
// than 2.x and 4.1, nodes defined twice, elements using undefined nodes).
GmshMesh ReadGmshMesh(const std::string& path, const GmshElementFilter& keep);

} // namespace cli
} // namespace tetmesher
