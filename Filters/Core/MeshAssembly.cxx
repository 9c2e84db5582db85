#include "MeshAssembly.h"

#include "TriangleIndex.h"

#include <algorithm>
#include <array>

namespace tetmesher
{
namespace
{
// A tet face by its two larger vertex ids (sorted) and its 4*t+f, for matching the faces that
// share their smallest vertex.
struct FaceEntry
{
  VertexId middle, largest;
  FaceRef face;
};
} // namespace

bool assembleRegionMesh(const std::vector<double>& points,
  const std::vector<std::int32_t>& tets,
  const std::vector<std::int32_t>& regionIds,
  RegionMesh& out,
  const std::vector<std::int32_t>& inputFaces)
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
  // Glue the faces: bucketed by their smallest vertex (a counting sort), then matched within
  // each bucket by their other two vertices. A node-based hash map of sorted faces took ~10 ms
  // for knot1.off's 15.7k tets (2026-12-02); the buckets are flat arrays, and the result
  // does not depend on how faces are matched (a face has at most one other side).
  const std::size_t vertexCount = points.size() / 3;
  std::vector<std::int32_t> bucketStart(vertexCount + 2, 0);
  for (std::size_t t = 0; t < tetCount; ++t)
  {
    const std::int32_t* v = &tets[4 * t];
    for (int i = 0; i < 4; ++i)
      if (v[i] < 0 || static_cast<std::size_t>(v[i]) >= vertexCount)
        return false; // no such point
    for (int f = 0; f < 4; ++f)
    {
      const int* fv = kFaceVertices[f];
      ++bucketStart[static_cast<std::size_t>(std::min({ v[fv[0]], v[fv[1]], v[fv[2]] })) + 2];
    }
  }
  for (std::size_t b = 2; b < bucketStart.size(); ++b)
    bucketStart[b] += bucketStart[b - 1];
  // bucketStart[v + 1] is where vertex v's bucket fills from; afterwards, where v + 1's begins.
  std::vector<FaceEntry> entries(4 * tetCount);
  for (std::size_t t = 0; t < tetCount; ++t)
  {
    for (int f = 0; f < 4; ++f)
    {
      const int* fv = kFaceVertices[f];
      VertexId a = tets[4 * t + static_cast<std::size_t>(fv[0])];
      VertexId b = tets[4 * t + static_cast<std::size_t>(fv[1])];
      VertexId c = tets[4 * t + static_cast<std::size_t>(fv[2])];
      if (a > b)
        std::swap(a, b);
      if (b > c)
        std::swap(b, c);
      if (a > b)
        std::swap(a, b);
      entries[static_cast<std::size_t>(bucketStart[static_cast<std::size_t>(a) + 1]++)] = {
        b, c, makeFaceRef(static_cast<TetId>(t), f)
      };
    }
  }
  for (std::size_t v = 0; v < vertexCount; ++v)
  {
    FaceEntry* first = entries.data() + bucketStart[v];
    FaceEntry* last = entries.data() + bucketStart[v + 1];
    std::sort(first,
      last,
      [](const FaceEntry& x, const FaceEntry& y)
      { return x.middle != y.middle ? x.middle < y.middle : x.largest < y.largest; });
    for (FaceEntry* e = first; e != last;)
    {
      FaceEntry* run = e + 1;
      while (run != last && run->middle == e->middle && run->largest == e->largest)
        ++run;
      if (run - e > 2)
        return false; // a third tet on this face
      if (run - e == 2)
      {
        const TetId t = faceTet(e[0].face), other = faceTet(e[1].face);
        const int f = faceIndex(e[0].face), otherFace = faceIndex(e[1].face);
        out.mesh.glue(t, f, other, otherFace);
        if (out.region[static_cast<std::size_t>(t)] != out.region[static_cast<std::size_t>(other)])
        {
          out.mesh.setConstrained(t, f, true);
          out.mesh.setConstrained(other, otherFace, true);
        }
      }
      e = run;
    }
  }
  for (std::size_t t = 0; t < tetCount; ++t)
    for (int f = 0; f < 4; ++f)
      if (out.mesh.neighbor(static_cast<TetId>(t), f) == kNoNeighbor)
        out.mesh.setConstrained(static_cast<TetId>(t), f, true);
  for (const std::int32_t face : inputFaces)
  {
    if (face < 0)
      continue;
    if (static_cast<std::size_t>(faceTet(face)) >= tetCount)
      return false;
    out.mesh.setConstrained(faceTet(face), faceIndex(face), true);
    const FaceRef across = out.mesh.neighbor(faceTet(face), faceIndex(face));
    if (across != kNoNeighbor)
      out.mesh.setConstrained(faceTet(across), faceIndex(across), true);
  }
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
