#include "MultiFaceRemoval.h"

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace tetmesher
{
namespace optimization
{

bool findMultiFaceRemoval(const Context& ctx, TetId t, int f, LocalMove& out)
{
  // Faces sandwiched between apexes a and b, oriented so that orient3d(face, a) > 0 (their
  // normal points toward b), each with its two tets. One face: the 2-3 flip.
  struct Sandwiched
  {
    std::array<VertexId, 3> v;
    TetId ta, tb;
  };
  if (ctx.mesh.isConstrained(t, f))
    return false;
  FaceRef n0 = ctx.mesh.neighbor(t, f);
  if (n0 == kNoNeighbor)
    return false;
  const VertexId a = ctx.mesh.vertex(t, f);
  const VertexId b = ctx.mesh.vertex(faceTet(n0), faceIndex(n0));
  if (!ctx.claim(b))
    return false; // a half's move: every tet it takes must be its own
  const int* fv = kFaceVertices[f];
  // Scratch reused between calls (this runs for every face of every bad tet).
  thread_local std::vector<Sandwiched> faces;
  thread_local std::vector<TetVertices> newTets;
  thread_local std::vector<std::pair<std::size_t, int>> edges; // boundary edge: face, edge index
  faces.assign(1,
    { { ctx.mesh.vertex(t, fv[0]), ctx.mesh.vertex(t, fv[1]), ctx.mesh.vertex(t, fv[2]) },
      t,
      faceTet(n0) });
  bool found = false;
  for (int iter = 0; iter < ctx.options.maxMultiFace; ++iter)
  {
    // Boundary edges of the face set (directed edges whose reverse is not in the set).
    edges.clear();
    for (std::size_t i = 0; i < faces.size(); ++i)
      for (int e = 0; e < 3; ++e)
      {
        VertexId u = faces[i].v[e], v = faces[i].v[(e + 1) % 3];
        std::size_t other = faces.size();
        for (std::size_t j = 0; j < faces.size() && other == faces.size(); ++j)
          for (int g = 0; g < 3; ++g)
            if (faces[j].v[g] == v && faces[j].v[(g + 1) % 3] == u)
              other = j;
        if (other == faces.size())
        {
          edges.push_back({ i, e });
          continue;
        }
        // An inner edge: the faces (u,v,a) and (u,v,b) are inside the removed region, so
        // they must join this face's tets to the other face's, unconstrained.
        VertexId w = faces[i].v[(e + 2) % 3];
        int wa = localIndex(ctx.mesh, faces[i].ta, w), wb = localIndex(ctx.mesh, faces[i].tb, w);
        FaceRef na = ctx.mesh.neighbor(faces[i].ta, wa), nb = ctx.mesh.neighbor(faces[i].tb, wb);
        if (ctx.mesh.isConstrained(faces[i].ta, wa) || ctx.mesh.isConstrained(faces[i].tb, wb) ||
          na == kNoNeighbor || nb == kNoNeighbor || faceTet(na) != faces[other].ta ||
          faceTet(nb) != faces[other].tb)
          return found;
      }
    // A vertex of the set on no boundary edge would vanish from the mesh.
    for (const Sandwiched& F : faces)
      for (VertexId x : F.v)
      {
        bool onBoundary = false;
        for (const auto& [i, e] : edges)
          onBoundary = onBoundary || faces[i].v[e] == x || faces[i].v[(e + 1) % 3] == x;
        if (!onBoundary)
          return found;
      }
    WorstOf oldMin;
    for (const Sandwiched& F : faces)
    {
      oldMin.add(ctx.quality(F.ta));
      oldMin.add(ctx.quality(F.tb));
    }
    // Every new tet's score (the growth below goes across the worst one), but its other
    // measure only while the set can still be taken: once the scores' minimum is not above
    // oldMin's and the best set's, the rule fails on the score whatever the rest.
    auto canWin = [&](double minScore)
    { return minScore > oldMin.score && (!found || minScore > out.newMin.score); };
    newTets.clear();
    WorstOf newMin;
    bool valid = true;
    std::size_t worst = 0;
    double worstScore = kInf;
    for (std::size_t k = 0; k < edges.size(); ++k)
    {
      const Sandwiched& F = faces[edges[k].first];
      int e = edges[k].second;
      TetVertices nt = { F.v[e], F.v[(e + 1) % 3], b, a };
      if (!ctx.positive(nt[0], nt[1], nt[2], nt[3]))
      {
        // Score -1, below any measured one: this is the worst tet, and the set is invalid.
        valid = false;
        worst = k;
        break;
      }
      Context::Staged m(ctx, nt[0], nt[1], nt[2], nt[3]);
      const double sc = m.values().score;
      newMin.score = std::min(newMin.score, sc);
      if (canWin(newMin.score))
        newMin.add(m.complete());
      if (sc < worstScore)
      {
        worstScore = sc;
        worst = k;
      }
      newTets.push_back(nt);
    }
    if (valid)
    {
      if (ctx.accept(newMin, oldMin) && (!found || newMin.score > out.newMin.score))
      {
        found = true;
        out.oldTets.clear();
        for (const Sandwiched& F : faces)
        {
          out.oldTets.push_back(F.ta);
          out.oldTets.push_back(F.tb);
        }
        out.newTets = newTets;
        out.newMin = newMin;
        out.kind = faces.size() == 1 ? 0 : 2;
      }
    }
    // Grow across the bottleneck edge (u,v) of face (u,v,w): the next sandwiched face is
    // (v,u,z) with tets (u,v,a,z) and (u,v,b,z) beyond the faces (u,v,a) and (u,v,b).
    const Sandwiched F = faces[edges[worst].first];
    const int e = edges[worst].second;
    const VertexId u = F.v[e], v = F.v[(e + 1) % 3], w = F.v[(e + 2) % 3];
    int wa = localIndex(ctx.mesh, F.ta, w), wb = localIndex(ctx.mesh, F.tb, w);
    if (ctx.mesh.isConstrained(F.ta, wa) || ctx.mesh.isConstrained(F.tb, wb))
      break;
    FaceRef na = ctx.mesh.neighbor(F.ta, wa), nb = ctx.mesh.neighbor(F.tb, wb);
    if (na == kNoNeighbor || nb == kNoNeighbor)
      break;
    TetId ta = faceTet(na), tb = faceTet(nb);
    VertexId z = ctx.mesh.vertex(ta, faceIndex(na));
    if (ctx.mesh.vertex(tb, faceIndex(nb)) != z || !ctx.claim(z))
      break;
    int ia = localIndex(ctx.mesh, ta, a);
    FaceRef mid = ctx.mesh.neighbor(ta, ia);
    if (mid == kNoNeighbor || faceTet(mid) != tb || ctx.mesh.isConstrained(ta, ia))
      break;
    bool seen = false;
    for (const Sandwiched& G : faces)
      seen = seen || G.ta == ta || G.tb == tb;
    if (seen || !ctx.positive(v, u, z, a))
      break;
    faces.push_back({ { v, u, z }, ta, tb });
  }
  return found;
}

} // namespace optimization
} // namespace tetmesher
