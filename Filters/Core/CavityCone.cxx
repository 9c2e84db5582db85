#include "CavityCone.h"

#include "Predicates.h"
#include "SurfaceInput.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

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

// Sorts `v` and drops repeats (the flat sets below: a cavity has at most a few hundred tets,
// and the node-based sets they replace cost more than the cone's exact tests).
template<typename T>
void sortUnique(std::vector<T>& v)
{
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

} // namespace

bool coneFromVertex(const TetMesh& mesh,
  VertexId apex,
  std::vector<TetId>& cavity,
  const std::function<bool(VertexId, VertexId)>& keepEdge,
  const CavityConeLimits& limits,
  std::vector<TetVertices>& cone)
{
  using Face = std::array<VertexId, 3>;
  // The cavity's tets are stamped with this call's epoch: membership in O(1) (a sorted list
  // searched and grown in place was half of this function's time on CAD parts' recovery).
  thread_local std::vector<std::uint32_t> stamp;
  thread_local std::uint32_t epoch = 0;
  thread_local std::vector<Face> apexFaces, boundaryAtApex, unmatched;
  thread_local std::vector<VertexId> vertices, coneVertices;
  thread_local std::vector<std::uint64_t> keptEdges, coneEdges; // edgeKey (SurfaceInput.h)
  if (stamp.size() < static_cast<std::size_t>(mesh.tetCapacity()))
    stamp.resize(static_cast<std::size_t>(mesh.tetCapacity()), 0);
  if (++epoch == 0)
  {
    std::fill(stamp.begin(), stamp.end(), 0);
    epoch = 1;
  }
  sortUnique(cavity);
  for (TetId t : cavity)
    stamp[static_cast<std::size_t>(t)] = epoch;
  auto isInside = [](TetId t) { return stamp[static_cast<std::size_t>(t)] == epoch; };
  // Growth: a boundary face that the apex does not strictly see takes the tet behind it in.
  // One pass over the growing list: a face found visible stays visible, and one that becomes
  // shared later is checked from the tet that came in (both sides of a constrained face are
  // read, so a face flagged on one side only is caught too).
  for (std::size_t k = 0; k < cavity.size(); ++k)
  {
    const TetId t = cavity[k];
    for (int f = 0; f < 4; ++f)
    {
      const FaceRef n = mesh.neighbor(t, f);
      const bool shared = n != kNoNeighbor && isInside(faceTet(n));
      if (shared)
      {
        if (mesh.isConstrained(t, f) || mesh.isConstrained(faceTet(n), faceIndex(n)))
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
      stamp[static_cast<std::size_t>(faceTet(n))] = epoch;
      cavity.push_back(faceTet(n));
    }
  }
  std::sort(cavity.begin(), cavity.end()); // the grown cavity, each tet once

  // The cone over the faces the apex sees; the faces through the apex must then pair up
  // (opposite orientations) except for the cavity's own boundary faces through the apex.
  cone.clear();
  apexFaces.clear();
  boundaryAtApex.clear();
  vertices.clear();
  keptEdges.clear();
  for (TetId t : cavity)
  {
    for (int i = 0; i < 4; ++i)
    {
      vertices.push_back(mesh.vertex(t, i));
      for (int j = i + 1; j < 4; ++j)
        if (keepEdge && keepEdge(mesh.vertex(t, i), mesh.vertex(t, j)))
          keptEdges.push_back(edgeKey(mesh.vertex(t, i), mesh.vertex(t, j)));
    }
    for (int f = 0; f < 4; ++f)
    {
      const FaceRef n = mesh.neighbor(t, f);
      if (n != kNoNeighbor && isInside(faceTet(n)))
        continue;
      const int* fv = kFaceVertices[f];
      const VertexId x = mesh.vertex(t, fv[0]), y = mesh.vertex(t, fv[1]),
                     z = mesh.vertex(t, fv[2]);
      if (x == apex || y == apex || z == apex)
      {
        boundaryAtApex.push_back(orientedKey(x, y, z));
        continue;
      }
      cone.push_back({ x, y, z, apex });
      // The cone tet's faces through the apex, outward: those opposite x, y and z.
      for (int g = 0; g < 3; ++g)
      {
        const int* gv = kFaceVertices[g];
        const TetVertices& c = cone.back();
        apexFaces.push_back(orientedKey(c[gv[0]], c[gv[1]], c[gv[2]]));
      }
    }
  }
  // Each oriented face through the apex is used once; those whose reverse no cone tet has
  // must be exactly the cavity's boundary faces through the apex.
  std::sort(apexFaces.begin(), apexFaces.end());
  if (std::adjacent_find(apexFaces.begin(), apexFaces.end()) != apexFaces.end())
    return false;
  unmatched.clear();
  for (const Face& face : apexFaces)
    if (!std::binary_search(
          apexFaces.begin(), apexFaces.end(), orientedKey(face[0], face[2], face[1])))
      unmatched.push_back(face);
  sortUnique(boundaryAtApex);
  if (unmatched != boundaryAtApex)
    return false;
  // Nothing of the cavity may be lost: its vertices and the edges to keep.
  coneVertices.clear();
  coneEdges.clear();
  for (const TetVertices& c : cone)
  {
    for (int i = 0; i < 4; ++i)
    {
      coneVertices.push_back(c[i]);
      for (int j = i + 1; j < 4; ++j)
        coneEdges.push_back(edgeKey(c[i], c[j]));
    }
  }
  sortUnique(vertices);
  sortUnique(coneVertices);
  if (coneVertices != vertices)
    return false;
  sortUnique(keptEdges);
  sortUnique(coneEdges);
  return std::includes(coneEdges.begin(), coneEdges.end(), keptEdges.begin(), keptEdges.end());
}

} // namespace tetmesher
