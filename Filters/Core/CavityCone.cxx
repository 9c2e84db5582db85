#include "CavityCone.h"

#include "Predicates.h"
#include "SurfaceInput.h"

#include <algorithm>
#include <array>
#include <map>
#include <set>

namespace tetmesher
{
namespace
{

// An oriented triangle with its smallest vertex first (the cyclic order, hence the
// orientation, is kept): the same face seen from its two sides gives two different keys.
std::array<VertexId, 3> orientedKey(VertexId x, VertexId y, VertexId z)
{
  if (y < x && y < z)
    return { y, z, x };
  if (z < x && z < y)
    return { z, x, y };
  return { x, y, z };
}

} // namespace

bool coneFromVertex(const TetMesh& mesh,
  VertexId apex,
  std::vector<TetId>& cavity,
  const std::function<bool(VertexId, VertexId)>& keepEdge,
  const CavityConeLimits& limits,
  std::vector<TetVertices>& cone)
{
  std::set<TetId> inside(cavity.begin(), cavity.end());
  cavity.assign(inside.begin(), inside.end());
  // Growth: a boundary face that the apex does not strictly see takes the tet behind it in.
  for (bool grown = true; grown;)
  {
    grown = false;
    for (std::size_t k = 0; k < cavity.size(); ++k)
    {
      const TetId t = cavity[k];
      for (int f = 0; f < 4; ++f)
      {
        const FaceRef n = mesh.neighbor(t, f);
        const bool shared = n != kNoNeighbor && inside.count(faceTet(n));
        if (shared)
        {
          if (mesh.isConstrained(t, f))
            return false; // an input triangle inside the cavity would be lost
          continue;
        }
        const int* fv = kFaceVertices[f];
        const VertexId x = mesh.vertex(t, fv[0]), y = mesh.vertex(t, fv[1]),
                       z = mesh.vertex(t, fv[2]);
        if (x == apex || y == apex || z == apex)
          continue;
        if (predicates::orient3d(mesh.point(x), mesh.point(y), mesh.point(z), mesh.point(apex)) > 0)
          continue;
        if (n == kNoNeighbor || mesh.isConstrained(t, f) ||
          static_cast<int>(cavity.size()) >= limits.maxTets)
          return false;
        inside.insert(faceTet(n));
        cavity.push_back(faceTet(n));
        grown = true;
      }
    }
  }
  std::sort(cavity.begin(), cavity.end());

  // The cone over the faces the apex sees; the faces through the apex must then pair up
  // (opposite orientations) except for the cavity's own boundary faces through the apex.
  cone.clear();
  std::map<std::array<VertexId, 3>, int> apexFaces; // oriented face -> uses
  std::set<std::array<VertexId, 3>> boundaryAtApex;
  std::set<VertexId> vertices;
  std::set<std::uint64_t> keptEdges; // edgeKey (SurfaceInput.h)
  for (TetId t : cavity)
  {
    for (int i = 0; i < 4; ++i)
    {
      vertices.insert(mesh.vertex(t, i));
      for (int j = i + 1; j < 4; ++j)
        if (keepEdge && keepEdge(mesh.vertex(t, i), mesh.vertex(t, j)))
          keptEdges.insert(edgeKey(mesh.vertex(t, i), mesh.vertex(t, j)));
    }
    for (int f = 0; f < 4; ++f)
    {
      const FaceRef n = mesh.neighbor(t, f);
      if (n != kNoNeighbor && inside.count(faceTet(n)))
        continue;
      const int* fv = kFaceVertices[f];
      const VertexId x = mesh.vertex(t, fv[0]), y = mesh.vertex(t, fv[1]),
                     z = mesh.vertex(t, fv[2]);
      if (x == apex || y == apex || z == apex)
      {
        boundaryAtApex.insert(orientedKey(x, y, z));
        continue;
      }
      cone.push_back({ x, y, z, apex });
      // The cone tet's faces through the apex, outward: those opposite x, y and z.
      for (int g = 0; g < 3; ++g)
      {
        const int* gv = kFaceVertices[g];
        const TetVertices& c = cone.back();
        ++apexFaces[orientedKey(c[gv[0]], c[gv[1]], c[gv[2]])];
      }
    }
  }
  std::set<std::array<VertexId, 3>> unmatched;
  for (const auto& [face, uses] : apexFaces)
  {
    if (uses != 1)
      return false;
    if (!apexFaces.count(orientedKey(face[0], face[2], face[1])))
      unmatched.insert(face);
  }
  if (unmatched != boundaryAtApex)
    return false;
  // Nothing of the cavity may be lost: its vertices and the edges to keep.
  std::set<VertexId> coneVertices;
  std::set<std::uint64_t> coneEdges;
  for (const TetVertices& c : cone)
  {
    for (int i = 0; i < 4; ++i)
    {
      coneVertices.insert(c[i]);
      for (int j = i + 1; j < 4; ++j)
        coneEdges.insert(edgeKey(c[i], c[j]));
    }
  }
  if (coneVertices != vertices)
    return false;
  return std::includes(coneEdges.begin(), coneEdges.end(), keptEdges.begin(), keptEdges.end());
}

} // namespace tetmesher
