#include "VertexInsertion.h"

#include "SurfaceInput.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace tetmesher
{
namespace optimization
{

namespace
{

// Grows the cavity from t for the vertex xv (already placed); keeps the best acceptable one
// in `out`, and in `valid` (when given) the best one whose cone is valid, acceptable or not.
bool growCavity(Context& ctx,
  TetId t,
  VertexId xv,
  int maxCavity,
  LocalMove& out,
  LocalMove* validOut = nullptr)
{
  TetMesh& m = ctx.mesh;
  // Scratch reused between calls: an insertion search grows 10-20 cavities.
  thread_local std::vector<TetId> cavity;
  cavity.assign(1, t);
  // Per tet slot: the stamp of the call whose cavity holds it (membership in O(1)).
  thread_local std::vector<std::uint32_t> inCavity;
  thread_local std::uint32_t cavityStamp = 0;
  if (inCavity.size() < static_cast<std::size_t>(m.tetCapacity()))
    inCavity.resize(static_cast<std::size_t>(m.tetCapacity()), 0);
  if (++cavityStamp == 0)
  {
    std::fill(inCavity.begin(), inCavity.end(), 0);
    cavityStamp = 1;
  }
  inCavity[static_cast<std::size_t>(t)] = cavityStamp;
  // Boundary faces of the cavity: (tet, face) and the tet's index in `cavity`.
  thread_local std::vector<std::pair<TetId, int>> faces;
  thread_local std::vector<std::size_t> faceOwner;
  // The cone's edges on the cavity boundary, as edgeKey: sorted as integers (as pairs of ids,
  // compared member-wise, the sort was a fifth of the insertion search on knot1.off at h).
  thread_local std::vector<std::uint64_t> edges;
  thread_local std::vector<TetVertices> newTets;
  // Per vertex: the iteration stamp of the last boundary face it was seen on (the check
  // that no cavity vertex vanishes, without sorting the faces' vertices).
  thread_local std::vector<std::uint32_t> seenOnFace;
  thread_local std::uint32_t stamp = 0;
  if (seenOnFace.size() < static_cast<std::size_t>(m.vertexCount()))
    seenOnFace.resize(static_cast<std::size_t>(m.vertexCount()), 0);
  // The new tet over face f of cavity[i] is the same in every iteration that has that face
  // (the cavity only grows, xv does not move): evaluated once, in slot 4 * i + f.
  struct Candidate
  {
    bool known = false, positive = false;
    TetEval eval;
  };
  thread_local std::vector<Candidate> candidates;
  candidates.clear();
  bool found = false;
  for (int iter = 0; iter < maxCavity; ++iter)
  {
    faces.clear();
    faceOwner.clear();
    for (std::size_t ci = 0; ci < cavity.size(); ++ci)
    {
      const TetId c = cavity[ci];
      for (int f = 0; f < 4; ++f)
      {
        FaceRef n = m.neighbor(c, f);
        if (n == kNoNeighbor || inCavity[static_cast<std::size_t>(faceTet(n))] != cavityStamp)
        {
          faces.push_back({ c, f });
          faceOwner.push_back(ci);
        }
        else if (m.isConstrained(c, f))
          return found; // a constraint inside the cavity (reached around it)
      }
    }
    // A cavity vertex on no boundary face would vanish from the mesh.
    if (++stamp == 0)
    {
      std::fill(seenOnFace.begin(), seenOnFace.end(), 0);
      stamp = 1;
    }
    for (const auto& [c, f] : faces)
      for (int k = 0; k < 3; ++k)
        seenOnFace[static_cast<std::size_t>(m.vertex(c, kFaceVertices[f][k]))] = stamp;
    for (TetId c : cavity)
      for (int i = 0; i < 4; ++i)
        if (seenOnFace[static_cast<std::size_t>(m.vertex(c, i))] != stamp)
          return found;
    candidates.resize(4 * cavity.size());
    newTets.clear();
    WorstOf newMin;
    bool valid = true;
    bool doomed = false;
    // The cavity grows across the face of the worst new tet that it may cross: a worst tet
    // on a constrained face (a surface triangle) would stop it at the first tet, where the
    // cone splits that tet and cannot be better (tets on the surface are the usual worst).
    std::size_t worst = faces.size();
    double worstScore = kInf;
    edges.clear();
    for (std::size_t i = 0; i < faces.size(); ++i)
    {
      const auto [c, f] = faces[i];
      const int* fv = kFaceVertices[f];
      TetVertices nt = { m.vertex(c, fv[0]), m.vertex(c, fv[1]), m.vertex(c, fv[2]), xv };
      for (int e = 0; e < 3; ++e)
        edges.push_back(edgeKey(nt[e], nt[(e + 1) % 3]));
      Candidate& cand = candidates[4 * faceOwner[i] + static_cast<std::size_t>(f)];
      if (!cand.known)
      {
        cand.known = true;
        cand.positive = ctx.positive(nt[0], nt[1], nt[2], nt[3]);
        if (cand.positive)
          cand.eval = ctx.eval(nt);
      }
      // As Context::scoreCandidate: -1 and an invalid move for a tet that is not positive.
      double sc = -1;
      if (cand.positive)
      {
        newMin.add(cand.eval);
        sc = cand.eval.score;
      }
      else
      {
        valid = false;
        // On a face the cavity never crosses, it stays in every larger cavity's cone.
        if (m.neighbor(c, f) == kNoNeighbor || m.isConstrained(c, f))
          doomed = true;
      }
      if (sc < worstScore && m.neighbor(c, f) != kNoNeighbor && !m.isConstrained(c, f))
      {
        worstScore = sc;
        worst = i;
      }
      newTets.push_back(nt);
    }
    if (valid)
    {
      // A cavity whose boundary is pinched along an edge would glue ambiguously.
      std::sort(edges.begin(), edges.end());
      for (std::size_t i = 0; i < edges.size() && valid; i += 2)
        valid = i + 1 < edges.size() && edges[i] == edges[i + 1] &&
          (i + 2 >= edges.size() || edges[i + 2] != edges[i]);
    }
    if (valid && validOut && (validOut->oldTets.empty() || newMin.score > validOut->newMin.score))
    {
      validOut->oldTets = cavity;
      validOut->newTets = newTets;
      validOut->newMin = newMin;
      validOut->kind = 3;
    }
    if (valid)
    {
      WorstOf oldMin;
      for (TetId c : cavity)
        oldMin.add(ctx.quality(c));
      if (ctx.accept(newMin, oldMin) && (!found || newMin.score > out.newMin.score))
      {
        found = true;
        out.oldTets = cavity;
        out.newTets = newTets;
        out.newMin = newMin;
        out.kind = 3;
      }
    }
    if (worst == faces.size() || doomed)
      break;
    cavity.push_back(faceTet(m.neighbor(faces[worst].first, faces[worst].second)));
    inCavity[static_cast<std::size_t>(cavity.back())] = cavityStamp;
  }
  return found;
}

// Moves xv (compass search, from `step` down to a hundredth of it) to maximise the worst
// score of the cone of `cone` (tets whose fourth vertex is xv), keeping every cone tet
// positive (exact) and preferring positions where the guarded measures stay above the
// floors of the acceptance rule against `old`. The candidate positions of insertion are
// rarely the best for the cone the cavity ends with (on a tet spanning two surface
// triangles, none of them is acceptable); this finds one that is.
void polishPosition(Context& ctx,
  VertexId xv,
  const std::vector<TetVertices>& cone,
  const WorstOf& old,
  double step)
{
  const double qFloor = std::min(old.q, ctx.floorQ);
  const double dihFloor = std::min(old.dihCosine, ctx.floorDihCosine);
  // The objective, exact when it exceeds `bound`; otherwise some value <= bound: the search
  // only compares against its best so far, so a position is dropped at its first tet at or
  // below that (tried first next time: most positions are rejected by the same tet), not
  // after measuring the whole cone. Same decisions as the full evaluation, a fraction of it.
  thread_local std::vector<std::size_t> order;
  order.resize(cone.size());
  for (std::size_t i = 0; i < cone.size(); ++i)
    order[i] = i;
  auto objective = [&](double bound)
  {
    WorstOf w;
    for (std::size_t k = 0; k < order.size(); ++k)
    {
      const TetVertices& nt = cone[order[k]];
      bool reject = !ctx.positive(nt[0], nt[1], nt[2], nt[3]);
      if (!reject)
      {
        const TetEval e = ctx.eval(nt);
        w.add(e);
        // Scores are in [0,1], so a guarded measure below its floor puts the objective
        // (score - 2) at -1 or below.
        reject = e.score <= bound || ((e.q < qFloor || e.dihCosine < dihFloor) && bound >= -1);
      }
      if (reject)
      {
        std::rotate(order.begin(),
          order.begin() + static_cast<std::ptrdiff_t>(k),
          order.begin() + static_cast<std::ptrdiff_t>(k) + 1);
        return w.score <= bound ? w.score : bound; // <= bound, never above it
      }
    }
    // Guarded measures below their floor: worse than any position that keeps them.
    return w.q >= qFloor && w.dihCosine >= dihFloor ? w.score : w.score - 2;
  };
  double* p = &ctx.mesh.coords[3 * static_cast<std::size_t>(xv)];
  double best = objective(-kInf);
  static const double kDirs[6][3] = {
    { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 }
  };
  const double minStep = 0.03 * step;
  for (int it = 0; it < 20 && step > minStep; ++it)
  {
    const std::array<double, 3> from = { p[0], p[1], p[2] };
    std::array<double, 3> bestPos = from;
    for (const auto& d : kDirs)
    {
      for (int k = 0; k < 3; ++k)
        p[k] = from[k] + step * d[k];
      const double v = objective(best);
      if (v > best)
      {
        best = v;
        bestPos = { p[0], p[1], p[2] };
      }
    }
    for (int k = 0; k < 3; ++k)
      p[k] = bestPos[k];
    if (bestPos == from)
      step *= 0.5;
  }
}

} // namespace

bool findVertexInsertion(Context& ctx, TetId t, LocalMove& out, int maxCavity)
{
  if (ctx.halves())
  {
    ctx.restricted = true; // a new vertex grows the shared arrays: after the halves
    return false;
  }
  TetMesh& m = ctx.mesh;
  // Candidate positions: the centroid, and over each face the apex of the regular tet on
  // that face (inside, toward the opposite vertex).
  std::vector<std::array<double, 3>> candidates;
  std::array<double, 3> centroid = { 0, 0, 0 };
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k)
      centroid[k] += 0.25 * m.point(m.vertex(t, i))[k];
  candidates.push_back(centroid);
  for (int f = 0; f < 4; ++f)
  {
    const int* fv = kFaceVertices[f];
    const double* a = m.point(m.vertex(t, fv[0]));
    const double* b = m.point(m.vertex(t, fv[1]));
    const double* c = m.point(m.vertex(t, fv[2]));
    double ab[3], ac[3], bc[3];
    for (int k = 0; k < 3; ++k)
    {
      ab[k] = b[k] - a[k];
      ac[k] = c[k] - a[k];
      bc[k] = c[k] - b[k];
    }
    double nrm[3] = {
      ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0]
    };
    double nn = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    if (!(nn > 0))
      continue;
    auto len = [](const double* v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); };
    double le = (len(ab) + len(ac) + len(bc)) / 3;
    std::array<double, 3> apex;
    for (int k = 0; k < 3; ++k) // the outward normal points away from the tet: go against it
      apex[k] = (a[k] + b[k] + c[k]) / 3 - nrm[k] / nn * le * std::sqrt(2.0 / 3.0);
    candidates.push_back(apex);
    if (ctx.options.measure == QualityMeasure::MinDihedral)
    {
      // Half as high too: seen from more of the cavities grown from a tet on the surface.
      // For the dihedral stage only (in the Q stage they end at a lower Q min on the test
      // grids).
      for (int k = 0; k < 3; ++k)
        apex[k] = (a[k] + b[k] + c[k]) / 3 - nrm[k] / nn * le * 0.5 * std::sqrt(2.0 / 3.0);
      candidates.push_back(apex);
    }
  }

  double h = 0;
  if (ctx.size)
    for (int i = 0; i < 4; ++i)
      h += 0.25 * ctx.sizeCopy[static_cast<std::size_t>(m.vertex(t, i))];
  const VertexId xv = m.addVertex(centroid[0], centroid[1], centroid[2]);
  if (ctx.size)
  {
    ctx.sizeCopy.resize(static_cast<std::size_t>(xv), h);
    ctx.sizeCopy.push_back(h);
  }
  bool found = false;
  std::array<double, 3> best = centroid;
  LocalMove cand, valid, bestValid;
  std::array<double, 3> bestValidPos = centroid;
  double* p = &m.coords[3 * static_cast<std::size_t>(xv)];
  for (const auto& x : candidates)
  {
    p[0] = x[0];
    p[1] = x[1];
    p[2] = x[2];
    valid.oldTets.clear();
    if (growCavity(ctx, t, xv, maxCavity, cand, &valid) &&
      (!found || cand.newMin.score > out.newMin.score))
    {
      found = true;
      out = cand;
      best = x;
    }
    if (!valid.oldTets.empty() &&
      (bestValid.oldTets.empty() || valid.newMin.score > bestValid.newMin.score))
    {
      bestValid = valid;
      bestValidPos = x;
    }
  }
  if (!found && !bestValid.oldTets.empty())
  {
    // None acceptable as placed: move the vertex within the best valid cavity, then judge
    // that cavity and the one grown anew from the moved vertex.
    p[0] = bestValidPos[0];
    p[1] = bestValidPos[1];
    p[2] = bestValidPos[2];
    WorstOf oldMin;
    for (TetId c : bestValid.oldTets)
      oldMin.add(ctx.quality(c));
    double le = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
      {
        const double* a = m.point(m.vertex(t, i));
        const double* b = m.point(m.vertex(t, j));
        le += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2])) /
          6;
      }
    polishPosition(ctx, xv, bestValid.newTets, oldMin, 0.25 * le);
    const std::array<double, 3> polished = { p[0], p[1], p[2] };
    WorstOf newMin;
    bool positive = true;
    for (const TetVertices& nt : bestValid.newTets)
      ctx.scoreCandidate(nt, newMin, positive);
    if (positive && ctx.accept(newMin, oldMin))
    {
      found = true;
      out = bestValid;
      out.newMin = newMin;
      best = polished;
    }
    if (growCavity(ctx, t, xv, maxCavity, cand) && (!found || cand.newMin.score > out.newMin.score))
    {
      found = true;
      out = cand;
      best = polished;
    }
  }
  if (!found)
  {
    m.coords.resize(m.coords.size() - 3);
    if (ctx.size)
      ctx.sizeCopy.resize(static_cast<std::size_t>(xv));
    return false;
  }
  p[0] = best[0];
  p[1] = best[1];
  p[2] = best[2];
  return true;
}

} // namespace optimization
} // namespace tetmesher
