#include "MeshAssembly.h"

#include "TriangleIndex.h"

#include <algorithm>
#include <array>
#include <unordered_map>

namespace tetmesher
{
namespace
{
struct FaceKeyHash
{
  std::size_t operator()(const std::array<VertexId, 3>& k) const
  {
    std::uint64_t h = static_cast<std::uint32_t>(k[0]);
    h = h * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint32_t>(k[1]);
    h = h * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint32_t>(k[2]);
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
};
// The vertex ids of face f of tet t, sorted: the key of the face whatever its orientation.
std::array<VertexId, 3> sortedFace(const std::vector<std::int32_t>& tets, std::size_t t, int f)
{
  std::array<VertexId, 3> key;
  for (int k = 0; k < 3; ++k)
    key[static_cast<std::size_t>(k)] = tets[4 * t + static_cast<std::size_t>(kFaceVertices[f][k])];
  std::sort(key.begin(), key.end());
  return key;
}
} // namespace

bool assembleRegionMesh(const std::vector<double>& points,
  const std::vector<std::int32_t>& tets,
  const std::vector<std::int32_t>& regionIds,
  RegionMesh& out)
{
  out = RegionMesh{};
  out.mesh.coords = points;
  const std::size_t tetCount = tets.size() / 4;
  out.mesh.tets.reserve(tets.size());
  for (std::size_t t = 0; t < tetCount; ++t)
  {
    out.mesh.addTet(tets[4 * t], tets[4 * t + 1], tets[4 * t + 2], tets[4 * t + 3]);
    out.region.push_back(regionIds.empty() ? 0 : regionIds[t]);
  }
  // Glue faces through a map from the sorted face to its first tet side.
  std::unordered_map<std::array<VertexId, 3>, FaceRef, FaceKeyHash> open;
  open.reserve(2 * tetCount);
  for (std::size_t t = 0; t < tetCount; ++t)
  {
    for (int f = 0; f < 4; ++f)
    {
      const std::array<VertexId, 3> key = sortedFace(tets, t, f);
      const TetId tet = static_cast<TetId>(t);
      auto [it, inserted] = open.emplace(key, makeFaceRef(tet, f));
      if (inserted)
        continue;
      if (it->second == kNoNeighbor)
        return false; // a third tet on this face
      const TetId other = faceTet(it->second);
      const int otherFace = faceIndex(it->second);
      out.mesh.glue(tet, f, other, otherFace);
      if (out.region[t] != out.region[static_cast<std::size_t>(other)])
      {
        out.mesh.setConstrained(tet, f, true);
        out.mesh.setConstrained(other, otherFace, true);
      }
      it->second = kNoNeighbor; // closed
    }
  }
  for (std::size_t t = 0; t < tetCount; ++t)
    for (int f = 0; f < 4; ++f)
      if (out.mesh.neighbor(static_cast<TetId>(t), f) == kNoNeighbor)
        out.mesh.setConstrained(static_cast<TetId>(t), f, true);
  return true;
}

void extractRegionMesh(const RegionMesh& in,
  std::vector<double>& points,
  std::vector<std::int32_t>& tets,
  std::vector<std::int32_t>& regionIds)
{
  points = in.mesh.coords;
  tets.clear();
  regionIds.clear();
  // Exactly: growing by doubling faulted in about twice the final size of fresh memory.
  tets.reserve(4 * static_cast<std::size_t>(in.mesh.liveTetCount()));
  regionIds.reserve(static_cast<std::size_t>(in.mesh.liveTetCount()));
  for (TetId t = 0; t < in.mesh.tetCapacity(); ++t)
  {
    if (in.mesh.isDeleted(t))
      continue;
    for (int i = 0; i < 4; ++i)
      tets.push_back(in.mesh.vertex(t, i));
    regionIds.push_back(in.region[static_cast<std::size_t>(t)]);
  }
}

std::vector<std::int32_t> tetFaceTriangles(const std::vector<std::int32_t>& tets,
  const std::int32_t* triangles,
  std::int32_t triangleCount)
{
  const TriangleIndex index(triangles, triangleCount);
  const VertexId maxVertex = index.largestVertex();
  std::vector<std::int32_t> faceTriangle(tets.size(), -1);
  for (std::size_t t = 0; t < tets.size() / 4; ++t)
  {
    // Most tets have an interior vertex (ids above every triangle's): skip the hashing of the
    // faces that contain it.
    const std::int32_t* tet = &tets[4 * t];
    int beyond = -1, beyondCount = 0;
    for (int i = 0; i < 4; ++i)
      if (tet[i] > maxVertex)
      {
        beyond = i;
        ++beyondCount;
      }
    if (beyondCount > 1)
      continue;
    for (int f = 0; f < 4; ++f)
    {
      if (beyondCount == 1 && f != beyond)
        continue; // face f contains every vertex but f
      const int* fv = kFaceVertices[f];
      const std::int32_t found = index.find(tet[fv[0]], tet[fv[1]], tet[fv[2]]);
      if (found >= 0)
        faceTriangle[4 * t + static_cast<std::size_t>(f)] = found;
    }
  }
  return faceTriangle;
}

std::vector<std::int32_t> firstFaceOfTriangles(const std::vector<std::int32_t>& faceTriangle,
  std::int32_t triangleCount)
{
  std::vector<std::int32_t> faces(static_cast<std::size_t>(triangleCount), -1);
  for (std::size_t face = 0; face < faceTriangle.size(); ++face)
  {
    const std::int32_t tri = faceTriangle[face];
    if (tri >= 0 && faces[static_cast<std::size_t>(tri)] < 0)
      faces[static_cast<std::size_t>(tri)] = static_cast<std::int32_t>(face); // = 4*t+f
  }
  return faces;
}

} // namespace tetmesher
