#include "Flips.h"

#include "FilteredPredicates.h"
#include "Predicates.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tetmesher
{
namespace
{
int priceTet(const FlipCost& c, const TetVertices& t)
{
  return c.tet ? c.tet(t) : 0;
}
int priceFace(const FlipCost& c, VertexId a, VertexId b, VertexId d)
{
  return c.face ? c.face(a, b, d) : 0;
}
int priceEdge(const FlipCost& c, VertexId a, VertexId b)
{
  return c.edge ? c.edge(a, b) : 0;
}

bool positive(const TetMesh& mesh, const TetVertices& t)
{
  const double *a = mesh.point(t[0]), *b = mesh.point(t[1]), *c = mesh.point(t[2]),
               *d = mesh.point(t[3]);
  // Four points on one axis-aligned plane (common in CAD input) are exactly flat: answer
  // without the slow exact stage that orient3d needs to prove a zero.
  for (int k = 0; k < 3; ++k)
  {
    if (a[k] == b[k] && a[k] == c[k] && a[k] == d[k])
      return false;
  }
  return predicates::orient3dFiltered(a, b, c, d) > 0;
}

TetVertices tetOf(const TetMesh& mesh, TetId t)
{
  return { mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2), mesh.vertex(t, 3) };
}
} // namespace

double tetShape(const TetMesh& mesh, const TetVertices& t)
{
  const double* p[4];
  for (int i = 0; i < 4; ++i)
    p[i] = mesh.point(t[i]);
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = p[1][k] - p[0][k];
    v[k] = p[2][k] - p[0][k];
    w[k] = p[3][k] - p[0][k];
  }
  double volume = std::fabs(u[0] * (v[1] * w[2] - v[2] * w[1]) -
                    u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])) /
    6.0;
  double sum = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      for (int k = 0; k < 3; ++k)
        sum += (p[i][k] - p[j][k]) * (p[i][k] - p[j][k]);
  if (sum <= 0)
    return 0;
  // Regular tet of edge 1: volume 1/(6 sqrt 2), sum of squares 6.
  double scale = std::pow(sum / 6.0, 1.5) / (6.0 * std::sqrt(2.0));
  return std::min(1.0, volume / scale);
}

bool betterMove(const FlipCandidate& a, const FlipCandidate& b)
{
  const int gainA = a.oldCost - a.newCost, gainB = b.oldCost - b.newCost;
  return gainA > gainB || (gainA == gainB && a.minQuality > b.minQuality);
}

bool flip23Candidate(const TetMesh& mesh, TetId t, int f, const FlipCost& cost, FlipCandidate& out)
{
  FaceRef n = mesh.neighbor(t, f);
  if (n == kNoNeighbor || mesh.isConstrained(t, f))
    return false;
  TetId u = faceTet(n);
  VertexId a = mesh.vertex(t, f);
  VertexId w = mesh.vertex(u, faceIndex(n));
  const int* fv = kFaceVertices[f];
  VertexId x = mesh.vertex(t, fv[0]), y = mesh.vertex(t, fv[1]), z = mesh.vertex(t, fv[2]);
  // (x,y,z) faces out of t; t = (x,y,z,a) up to an even permutation. Replacing one face
  // vertex by w keeps the orientation when aw crosses the face.
  out.newTets = { { x, y, w, a }, { y, z, w, a }, { z, x, w, a } };
  for (const TetVertices& nt : out.newTets)
  {
    if (!positive(mesh, nt))
      return false;
  }
  out.oldTets = { t, u };
  out.oldCost =
    priceTet(cost, tetOf(mesh, t)) + priceTet(cost, tetOf(mesh, u)) + priceFace(cost, x, y, z);
  out.newCost = priceEdge(cost, a, w) + priceFace(cost, a, w, x) + priceFace(cost, a, w, y) +
    priceFace(cost, a, w, z);
  out.minQuality = 1;
  for (const TetVertices& nt : out.newTets)
  {
    out.newCost += priceTet(cost, nt);
    out.minQuality = std::min(out.minQuality, tetShape(mesh, nt));
  }
  return true;
}

bool edgeRemovalCandidate(const TetMesh& mesh,
  TetId t,
  VertexId p,
  VertexId q,
  const FlipCost& cost,
  FlipCandidate& out,
  int maxRing)
{
  // Scratch reused between calls (this runs for every edge of every flip search).
  thread_local std::vector<TetId> shell;
  thread_local std::vector<VertexId> ring;
  return edgeShell(mesh, t, p, q, shell, ring) &&
    edgeRemovalCandidate(mesh, p, q, shell, ring, cost, out, maxRing);
}

bool edgeRemovalCandidate(const TetMesh& mesh,
  VertexId p,
  VertexId q,
  const std::vector<TetId>& shell,
  const std::vector<VertexId>& ring,
  const FlipCost& cost,
  FlipCandidate& out,
  int maxRing)
{
  const int n = static_cast<int>(ring.size());
  if (n < 3 || n > maxRing)
    return false;
  for (TetId s : shell)
  {
    for (int f = 0; f < 4; ++f)
    {
      VertexId opposite = mesh.vertex(s, f);
      if (opposite != p && opposite != q && mesh.isConstrained(s, f))
        return false; // a face around the edge is an input face
    }
  }

  // Ring triangles (i<j<k) give the tets (ri,rj,rk,q) and (rj,ri,rk,p), both positive when
  // the triangle separates p from q properly. Whether they are, by triangle (-1: not tested).
  thread_local std::vector<signed char> splits;
  splits.assign(static_cast<std::size_t>(n) * n * n, -1);
  auto splitsPositive = [&](int i, int j, int k)
  {
    signed char& known = splits[(static_cast<std::size_t>(i) * n + j) * n + k];
    if (known < 0)
      known = positive(mesh, { ring[i], ring[j], ring[k], q }) &&
        positive(mesh, { ring[j], ring[i], ring[k], p });
    return known == 1;
  };
  // Most shells priced have no valid triangulation (anchor.off: 2 of 3): find that out by
  // orientations alone before pricing any tet. triangulable(i, k): the sub-polygon i..k has
  // a triangulation of positive splits (a pair of ring neighbours trivially has).
  thread_local std::vector<char> triangulable;
  triangulable.assign(static_cast<std::size_t>(n) * n, 0);
  auto canSplit = [&](int i, int k)
  { return k - i < 2 || triangulable[static_cast<std::size_t>(i) * n + k]; };
  for (int span = 2; span < n; ++span)
  {
    for (int i = 0; i + span < n; ++i)
    {
      const int k = i + span;
      for (int j = i + 1; j < k; ++j)
      {
        if (canSplit(i, j) && canSplit(j, k) && splitsPositive(i, j, k))
        {
          triangulable[static_cast<std::size_t>(i) * n + k] = 1;
          break;
        }
      }
    }
  }
  if (!canSplit(0, n - 1))
    return false;

  struct Score
  {
    int cost = std::numeric_limits<int>::max();
    double quality = -1;
    int split = -1;
    bool valid() const { return split >= 0; }
  };
  auto better = [](int c, double qual, const Score& s)
  { return !s.valid() || c < s.cost || (c == s.cost && qual > s.quality); };
  thread_local std::vector<Score> best;
  best.assign(static_cast<std::size_t>(n) * n, Score());
  auto at = [&](int i, int k) -> Score& { return best[static_cast<std::size_t>(i) * n + k]; };
  // Cost of the edge (ring[a], ring[b]) and its faces with p and q, priced once per pair
  // (-1: not yet) instead of once per triangle that uses the pair.
  thread_local std::vector<int> pairCost;
  pairCost.assign(static_cast<std::size_t>(n) * n, -1);
  auto pricePair = [&](int a, int b)
  {
    int& c = pairCost[static_cast<std::size_t>(a) * n + b];
    if (c < 0)
      c = priceEdge(cost, ring[a], ring[b]) + priceFace(cost, p, ring[a], ring[b]) +
        priceFace(cost, q, ring[a], ring[b]);
    return c;
  };
  for (int span = 2; span < n; ++span)
  {
    for (int i = 0; i + span < n; ++i)
    {
      int k = i + span;
      for (int j = i + 1; j < k; ++j)
      {
        int c = 0;
        double qual = 1;
        for (auto [a, b] : { std::pair<int, int>{ i, j }, std::pair<int, int>{ j, k } })
        {
          if (b - a < 2)
            continue;
          const Score& sub = at(a, b);
          if (!sub.valid())
          {
            c = -1;
            break;
          }
          c += sub.cost + pricePair(a, b);
          qual = std::min(qual, sub.quality);
        }
        // Costs are non-negative: a split already dearer than the best one cannot win, so it
        // is dropped before its orientation tests (the same choice, fewer predicates).
        const Score& current = at(i, k);
        if (c < 0 || (current.valid() && c > current.cost))
          continue;
        if (!splitsPositive(i, j, k))
          continue;
        TetVertices upper = { ring[i], ring[j], ring[k], q };
        TetVertices lower = { ring[j], ring[i], ring[k], p };
        c += priceTet(cost, upper) + priceTet(cost, lower) +
          priceFace(cost, ring[i], ring[j], ring[k]);
        if (current.valid() && c > current.cost)
          continue; // shapes only break ties
        qual = std::min({ qual, tetShape(mesh, upper), tetShape(mesh, lower) });
        if (better(c, qual, current))
          at(i, k) = { c, qual, j };
      }
    }
  }
  const Score& root = at(0, n - 1);
  if (!root.valid())
    return false;

  out.oldTets = shell;
  out.oldCost = priceEdge(cost, p, q);
  for (int k = 0; k < n; ++k)
  {
    out.oldCost += priceFace(cost, p, q, ring[k]) + priceTet(cost, tetOf(mesh, shell[k]));
  }
  out.newCost = root.cost;
  out.minQuality = root.quality;
  out.newTets.clear();
  thread_local std::vector<std::pair<int, int>> stack;
  stack.assign(1, { 0, n - 1 });
  while (!stack.empty())
  {
    auto [i, k] = stack.back();
    stack.pop_back();
    if (k - i < 2)
      continue;
    int j = at(i, k).split;
    out.newTets.push_back({ ring[i], ring[j], ring[k], q });
    out.newTets.push_back({ ring[j], ring[i], ring[k], p });
    stack.push_back({ i, j });
    stack.push_back({ j, k });
  }
  return true;
}

} // namespace tetmesher
