// Exhaustive mesh checks. They use the exact predicates only, so a reported failure is a
// real defect of the mesh, never a rounding artefact.
#include "MeshValidation.h"

#include "Predicates.h"

#include <algorithm>
#include <sstream>

namespace tetmesher
{

namespace
{

std::string tetString(const TetMesh& mesh, TetId t)
{
  std::ostringstream s;
  s << "tet " << t << " (" << mesh.vertex(t, 0) << ", " << mesh.vertex(t, 1) << ", "
    << mesh.vertex(t, 2) << ", " << mesh.vertex(t, 3) << ")";
  return s.str();
}

void sortedFace(const TetMesh& mesh, TetId t, int f, VertexId out[3])
{
  for (int k = 0; k < 3; ++k)
    out[k] = mesh.vertex(t, kFaceVertices[f][k]);
  std::sort(out, out + 3);
}

// The first non-empty message of check(t, f, n) over the faces f of live tets t that have a
// neighbour n (each glued face seen from both sides).
template<typename Check>
std::string firstGluedFaceDefect(const TetMesh& mesh, Check check)
{
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    if (mesh.isDeleted(t))
      continue;
    for (int f = 0; f < 4; ++f)
    {
      const FaceRef n = mesh.neighbor(t, f);
      if (n == kNoNeighbor)
        continue;
      std::string defect = check(t, f, n);
      if (!defect.empty())
        return defect;
    }
  }
  return {};
}

} // namespace

std::string checkOrientation(const TetMesh& mesh)
{
  const VertexId nv = mesh.vertexCount();
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    if (mesh.isDeleted(t))
      continue;
    VertexId v[4];
    for (int k = 0; k < 4; ++k)
    {
      v[k] = mesh.vertex(t, k);
      if (v[k] < 0 || v[k] >= nv)
        return tetString(mesh, t) + " has an invalid vertex id";
    }
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (v[i] == v[j])
          return tetString(mesh, t) + " repeats a vertex";
    const int s =
      predicates::orient3d(mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]), mesh.point(v[3]));
    if (s <= 0)
      return tetString(mesh, t) + (s == 0 ? " is flat" : " is inverted");
  }
  return {};
}

std::string checkAdjacency(const TetMesh& mesh, bool requireSymmetricConstraints)
{
  return firstGluedFaceDefect(mesh,
    [&](TetId t, int f, FaceRef n) -> std::string
    {
      const TetId u = faceTet(n);
      const int g = faceIndex(n);
      std::ostringstream where;
      where << tetString(mesh, t) << " face " << f << " -> tet " << u << " face " << g;
      if (u < 0 || u >= mesh.tetCapacity() || mesh.isDeleted(u))
        return where.str() + ": neighbour is not a live tet";
      if (mesh.neighbor(u, g) != makeFaceRef(t, f))
        return where.str() + ": neighbour does not point back";
      VertexId a[3], b[3];
      sortedFace(mesh, t, f, a);
      sortedFace(mesh, u, g, b);
      if (!std::equal(a, a + 3, b))
        return where.str() + ": glued faces have different vertices";
      if (requireSymmetricConstraints && mesh.isConstrained(t, f) != mesh.isConstrained(u, g))
        return where.str() + ": constrained flag set on one side only";
      return {};
    });
}

std::string checkDelaunay(const TetMesh& mesh, bool skipConstrained)
{
  return firstGluedFaceDefect(mesh,
    [&](TetId t, int f, FaceRef n) -> std::string
    {
      const TetId u = faceTet(n);
      if (skipConstrained && (mesh.isConstrained(t, f) || mesh.isConstrained(u, faceIndex(n))))
        return {};
      const VertexId opposite = mesh.vertex(u, faceIndex(n));
      const int s = predicates::insphereSoS(
        mesh, mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2), mesh.vertex(t, 3), opposite);
      if (s < 0)
        return {};
      std::ostringstream msg;
      msg << tetString(mesh, t) << " face " << f << ": opposite vertex " << opposite << " of tet "
          << u << " is " << (s > 0 ? "inside" : "on") << " its circumsphere";
      return msg.str();
    });
}

std::string checkVerticesPresent(const TetMesh& mesh,
  VertexId count,
  const std::vector<VertexId>& absent)
{
  std::vector<char> seen(static_cast<std::size_t>(std::max<VertexId>(count, 0)), 0);
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    if (mesh.isDeleted(t))
      continue;
    for (int k = 0; k < 4; ++k)
    {
      const VertexId v = mesh.vertex(t, k);
      if (v >= 0 && v < count)
        seen[static_cast<std::size_t>(v)] = 1;
    }
  }
  for (VertexId v : absent)
    if (v >= 0 && v < count)
    {
      if (seen[static_cast<std::size_t>(v)])
        return "vertex " + std::to_string(v) + " should be absent but is in a tet";
      seen[static_cast<std::size_t>(v)] = 1;
    }
  for (VertexId v = 0; v < count; ++v)
    if (!seen[static_cast<std::size_t>(v)])
      return "vertex " + std::to_string(v) + " is in no tet";
  return {};
}

std::string validateDelaunayMesh(const TetMesh& mesh,
  VertexId count,
  const std::vector<VertexId>& absent)
{
  std::string msg = checkOrientation(mesh);
  if (msg.empty())
    msg = checkAdjacency(mesh);
  if (msg.empty())
    msg = checkDelaunay(mesh);
  if (msg.empty())
    msg = checkVerticesPresent(mesh, count, absent);
  return msg;
}

long double volumeWithoutVertices(const TetMesh& mesh, VertexId firstExcluded)
{
  long double total = 0;
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    if (mesh.isDeleted(t))
      continue;
    bool keep = true;
    for (int k = 0; k < 4; ++k)
      keep = keep && mesh.vertex(t, k) < firstExcluded;
    if (!keep)
      continue;
    const double* p[4];
    for (int k = 0; k < 4; ++k)
      p[k] = mesh.point(mesh.vertex(t, k));
    long double m[3][3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        m[r][c] = static_cast<long double>(p[r][c]) - p[3][c];
    const long double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
      m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
      m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    total += det / 6;
  }
  return total;
}

} // namespace tetmesher
