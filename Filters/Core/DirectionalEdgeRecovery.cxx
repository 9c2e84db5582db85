#include "DirectionalEdgeRecovery.h"

#include "RecoveryGeometry.h"

namespace tetmesher
{
namespace
{

// The points of tet t.
struct TetPoints
{
  const double* p[4];
  TetPoints(const TetMesh& mesh, TetId t)
    : p{ mesh.point(mesh.vertex(t, 0)),
      mesh.point(mesh.vertex(t, 1)),
      mesh.point(mesh.vertex(t, 2)),
      mesh.point(mesh.vertex(t, 3)) }
  {
  }
};

// Where the segment from a towards b leaves a's star: the tet whose closed cone at a holds it
// (a is its vertex `apex`), and how many of the cone's three faces hold it too (0: it leaves
// through the far face's interior; 1: through the open edge of the far face that lies in face
// `onFace`'s plane, onFace being the local index of the vertex opposite it; 2: along an edge of
// the star, through a vertex). `edge`: b is a vertex of the star, (a,b) is an edge already.
struct Exit
{
  TetId tet = -1;
  int apex = -1;
  int onFaces = 0;
  int onFace = -1;
  bool edge = false;
};

// The cones of a's star tile the space around a, so one of them holds the segment (a valid
// mesh, a inside its box). In it, replacing a far vertex by b gives a positive or flat tet.
// When (a,b) is an edge, only the tets around it hold the segment, and each has b: so b is
// looked for in each tet before its cone.
Exit exitOfStar(const TetMesh& mesh, const std::vector<TetId>& star, VertexId a, VertexId b)
{
  const double* pb = mesh.point(b);
  for (TetId t : star)
  {
    Exit exit;
    if (localIndex(mesh, t, b) >= 0)
    {
      exit.edge = true;
      return exit;
    }
    const int apex = localIndex(mesh, t, a);
    const TetPoints tet(mesh, t);
    bool holds = true;
    for (int k = 0; k < 4 && holds; ++k)
    {
      if (k == apex)
        continue;
      const int o = geometry::orientWithVertexReplaced(tet.p, k, pb);
      if (o < 0)
        holds = false;
      else if (o == 0)
      {
        ++exit.onFaces;
        exit.onFace = k;
      }
    }
    if (holds)
    {
      exit.tet = t;
      exit.apex = apex;
      return exit;
    }
  }
  return Exit();
}

// Flips from a towards b; true when (a,b) is then an edge.
bool flipFrom(TetMesh& mesh,
  VertexTetIndex& index,
  VertexId a,
  VertexId b,
  const std::function<bool(VertexId, VertexId)>& keepEdge,
  const std::function<void(const FlipCandidate&, bool)>& apply,
  int maxFlips,
  std::vector<TetId>& star)
{
  const FlipCost none; // validity alone: the candidates then prefer the best shaped
  FlipCandidate move;
  for (int flip = 0;; ++flip)
  {
    vertexStar(mesh, index, a, star);
    const Exit exit = exitOfStar(mesh, star, a, b);
    if (exit.edge)
      return true;
    if (exit.tet < 0 || exit.onFaces >= 2 || flip == maxFlips)
      return false;
    const TetId t = exit.tet;
    // The far face's edge without vertex k of t (k not the apex).
    auto farEdgeWithout = [&](int k, VertexId& p, VertexId& q)
    {
      int n = 0;
      for (int i = 0; i < 4; ++i)
        if (i != exit.apex && i != k)
          (n++ == 0 ? p : q) = mesh.vertex(t, i);
    };
    auto removeEdge = [&](VertexId p, VertexId q)
    {
      if (keepEdge(p, q) || !edgeRemovalCandidate(mesh, t, p, q, none, move))
        return false;
      apply(move, false);
      return true;
    };
    if (exit.onFaces == 1)
    {
      VertexId p, q;
      farEdgeWithout(exit.onFace, p, q);
      if (!removeEdge(p, q))
        return false;
      continue;
    }
    if (flip23Candidate(mesh, t, exit.apex, none, move))
    {
      apply(move, true);
      continue;
    }
    // The 2-3 flip is invalid (or the face is constrained, or on the hull: then no move).
    const FaceRef across = mesh.neighbor(t, exit.apex);
    if (across == kNoNeighbor || mesh.isConstrained(t, exit.apex))
      return false;
    // It would make the tet (a, p, q, s) for each far edge pq, s the apex across: an edge
    // whose tet is not positive blocks it.
    const VertexId s = mesh.vertex(faceTet(across), faceIndex(across));
    const TetPoints tet(mesh, t);
    bool removed = false;
    for (int k = 0; k < 4 && !removed; ++k)
    {
      if (k == exit.apex || geometry::orientWithVertexReplaced(tet.p, k, mesh.point(s)) > 0)
        continue;
      VertexId p, q;
      farEdgeWithout(k, p, q);
      removed = removeEdge(p, q);
    }
    if (!removed)
      return false;
  }
}

} // namespace

bool flipEdgeIntoMesh(TetMesh& mesh,
  VertexTetIndex& index,
  VertexId a,
  VertexId b,
  const std::function<bool(VertexId, VertexId)>& keepEdge,
  const std::function<void(const FlipCandidate&, bool)>& apply,
  const DirectionalRecoveryOptions& options)
{
  thread_local std::vector<TetId> star;
  return flipFrom(mesh, index, a, b, keepEdge, apply, options.maxFlips, star) ||
    flipFrom(mesh, index, b, a, keepEdge, apply, options.maxFlips, star);
}

} // namespace tetmesher
