// Exact predicates: the public entry points run the inline filters of FilteredPredicates.h;
// this file holds the exact fallbacks (expansion arithmetic) and the symbolic perturbation.
//
// The exact versions evaluate the same determinants as the filters, but every coordinate
// difference is kept as a two-component expansion (twoDiff is exact) and every product and
// sum as an expansion, so the sign is the sign of the exact real determinant.
#include "Predicates.h"

#include "ExpansionArithmetic.h"
#include "FilteredPredicates.h"

#include <algorithm>
#include <vector>

namespace tetmesher
{
namespace predicates
{

namespace
{

using namespace expansion;

// An expansion living in a scratch arena: `length` components at `data`.
struct Exp
{
  double* data;
  int length;
};

// Bump allocator for the exact paths: one per thread, grown once, reset per predicate.
// Worst-case sizes of the insphere expansions are tens of thousands of doubles; in practice
// zero elimination keeps them to a handful, so the arena stays in cache.
class Arena
{
public:
  void reset() { used = 0; }
  double* take(std::size_t n)
  {
    if (used + n > storage.size())
    {
      // Never reallocate while pointers are live: chain a fresh block instead.
      blocks.emplace_back(std::max<std::size_t>(n, 1u << 16));
      return blocks.back().data();
    }
    double* p = storage.data() + used;
    used += n;
    return p;
  }
  void releaseExtraBlocks()
  {
    if (!blocks.empty())
    {
      std::size_t extra = 0;
      for (auto& b : blocks)
        extra += b.size();
      blocks.clear();
      storage.assign(storage.size() + extra, 0.0);
    }
  }

private:
  std::vector<double> storage = std::vector<double>(1u << 17);
  std::vector<std::vector<double>> blocks;
  std::size_t used = 0;
};

Arena& arena()
{
  thread_local Arena instance;
  return instance;
}

Exp difference(Arena& ar, double a, double b)
{
  Exp r{ ar.take(2), 0 };
  double x, y;
  twoDiff(a, b, x, y);
  if (y != 0.0)
    r.data[r.length++] = y;
  r.data[r.length++] = x;
  return r;
}

Exp product(Arena& ar, Exp e, Exp f)
{
  const std::size_t n = 2 * static_cast<std::size_t>(e.length) * f.length;
  Exp r{ ar.take(n > 0 ? n : 1), 0 };
  double* scratch = ar.take(2 * n + 1);
  r.length = multiplyExpansions(e.length, e.data, f.length, f.data, r.data, scratch);
  return r;
}

Exp sum(Arena& ar, Exp e, Exp f)
{
  Exp r{ ar.take(static_cast<std::size_t>(e.length) + f.length + 1), 0 };
  r.length = sumExpansions(e.length, e.data, f.length, f.data, r.data);
  return r;
}

Exp diff(Arena& ar, Exp e, Exp f)
{
  Exp r{ ar.take(static_cast<std::size_t>(e.length) + f.length + 1), 0 };
  r.length = diffExpansions(e.length, e.data, f.length, f.data, r.data);
  return r;
}

// x1*y2 - x2*y1
Exp minor2(Arena& ar, Exp x1, Exp y1, Exp x2, Exp y2)
{
  return diff(ar, product(ar, x1, y2), product(ar, x2, y1));
}

int sign(Exp e)
{
  return expansionSign(e.length, e.data);
}

} // namespace

int orient3dExact(const double* a, const double* b, const double* c, const double* d)
{
  Arena& ar = arena();
  ar.reset();
  const Exp adx = difference(ar, a[0], d[0]), bdx = difference(ar, b[0], d[0]),
            cdx = difference(ar, c[0], d[0]);
  const Exp ady = difference(ar, a[1], d[1]), bdy = difference(ar, b[1], d[1]),
            cdy = difference(ar, c[1], d[1]);
  const Exp adz = difference(ar, a[2], d[2]), bdz = difference(ar, b[2], d[2]),
            cdz = difference(ar, c[2], d[2]);
  // adz*(bdx*cdy - cdx*bdy) + bdz*(cdx*ady - adx*cdy) + cdz*(adx*bdy - bdx*ady)
  const Exp t1 = product(ar, adz, minor2(ar, bdx, bdy, cdx, cdy));
  const Exp t2 = product(ar, bdz, minor2(ar, cdx, cdy, adx, ady));
  const Exp t3 = product(ar, cdz, minor2(ar, adx, ady, bdx, bdy));
  const int s = sign(sum(ar, sum(ar, t1, t2), t3));
  ar.releaseExtraBlocks();
  return s;
}

int insphereExact(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* e)
{
  Arena& ar = arena();
  ar.reset();
  const Exp aex = difference(ar, a[0], e[0]), bex = difference(ar, b[0], e[0]),
            cex = difference(ar, c[0], e[0]), dex = difference(ar, d[0], e[0]);
  const Exp aey = difference(ar, a[1], e[1]), bey = difference(ar, b[1], e[1]),
            cey = difference(ar, c[1], e[1]), dey = difference(ar, d[1], e[1]);
  const Exp aez = difference(ar, a[2], e[2]), bez = difference(ar, b[2], e[2]),
            cez = difference(ar, c[2], e[2]), dez = difference(ar, d[2], e[2]);

  const Exp ab = minor2(ar, aex, aey, bex, bey);
  const Exp bc = minor2(ar, bex, bey, cex, cey);
  const Exp cd = minor2(ar, cex, cey, dex, dey);
  const Exp da = minor2(ar, dex, dey, aex, aey);
  const Exp ac = minor2(ar, aex, aey, cex, cey);
  const Exp bd = minor2(ar, bex, bey, dex, dey);

  // abc = aez*bc - bez*ac + cez*ab, etc. (cofactors of the lift column)
  const Exp abc =
    sum(ar, diff(ar, product(ar, aez, bc), product(ar, bez, ac)), product(ar, cez, ab));
  const Exp bcd =
    sum(ar, diff(ar, product(ar, bez, cd), product(ar, cez, bd)), product(ar, dez, bc));
  const Exp cda =
    sum(ar, sum(ar, product(ar, cez, da), product(ar, dez, ac)), product(ar, aez, cd));
  const Exp dab =
    sum(ar, sum(ar, product(ar, dez, ab), product(ar, aez, bd)), product(ar, bez, da));

  auto lift = [&ar](Exp x, Exp y, Exp z)
  { return sum(ar, sum(ar, product(ar, x, x), product(ar, y, y)), product(ar, z, z)); };
  const Exp alift = lift(aex, aey, aez), blift = lift(bex, bey, bez);
  const Exp clift = lift(cex, cey, cez), dlift = lift(dex, dey, dez);

  const Exp left = diff(ar, product(ar, dlift, abc), product(ar, clift, dab));
  const Exp right = diff(ar, product(ar, blift, cda), product(ar, alift, bcd));
  const int s = sign(sum(ar, left, right));
  ar.releaseExtraBlocks();
  return s;
}

int orient2dExact(double ax, double ay, double bx, double by, double cx, double cy)
{
  Arena& ar = arena();
  ar.reset();
  const Exp acx = difference(ar, ax, cx), bcx = difference(ar, bx, cx);
  const Exp acy = difference(ar, ay, cy), bcy = difference(ar, by, cy);
  const int s = sign(minor2(ar, acx, acy, bcx, bcy));
  ar.releaseExtraBlocks();
  return s;
}

// Simulation of simplicity on the lifted points (Edelsbrunner-Muecke 1990; the same rule as
// Devillers-Teillaud's perturbed power test with zero weights).
//
// Rule: the lifted coordinate of vertex i is |p_i|^2 + eps^(K - i) for an infinitesimal
// eps > 0 and a large K, so the vertex with the LARGEST id has the LARGEST perturbation.
// The in-sphere determinant is affine in each lifted coordinate and contains each exactly
// once, so the perturbed value is insphere + sum_i eps^(K - i) * C_i where C_i is the
// cofactor of vertex i's lift: an orientation of the four other points. Its sign is the sign
// of the first non-zero C_i taken by decreasing id. Concretely, for the tuple (p0..p4):
//   C_4 = -orient3d(p0, p1, p2, p3)        (lifting e raises it out of the sphere)
//   C_k = +orient3d(p0..p3 with p_k replaced by p4), k < 4   (alternation: swap p_k, p4)
// Since (p0..p3) is positively oriented, C_4 != 0, so the result is never 0. The perturbed
// determinant is a single polynomial in eps, so the answers of different tuples are
// mutually consistent (they are the exact answers for one perturbed point set).
int insphereTieBreak(const double* const points[5], const VertexId ids[5])
{
  int order[5] = { 0, 1, 2, 3, 4 };
  std::sort(order, order + 5, [ids](int i, int j) { return ids[i] > ids[j]; });
  for (int k : order)
  {
    int s;
    if (k == 4)
      s = -orient3dFiltered(points[0], points[1], points[2], points[3]);
    else
    {
      const double* q[4] = { points[0], points[1], points[2], points[3] };
      q[k] = points[4];
      s = orient3dFiltered(q[0], q[1], q[2], q[3]);
    }
    if (s != 0)
      return s;
  }
  return 0; // only for a flat (a,b,c,d), which violates the precondition
}

int orient3d(const double* a, const double* b, const double* c, const double* d)
{
  return orient3dFiltered(a, b, c, d);
}

int insphere(const double* a, const double* b, const double* c, const double* d, const double* e)
{
  return insphereFiltered(a, b, c, d, e);
}

// The projection keeps the two remaining axes in cyclic order (drop z: (x,y); drop x: (y,z);
// drop y: (z,x)) so that the 2D orientation agrees with the 3D normal's component along the
// dropped axis.
int orient2d(const double* a, const double* b, const double* c, int dropAxis)
{
  const int i = (dropAxis + 1) % 3, j = (dropAxis + 2) % 3;
  const double detLeft = (a[i] - c[i]) * (b[j] - c[j]);
  const double detRight = (a[j] - c[j]) * (b[i] - c[i]);
  const double det = detLeft - detRight;
  const double bound = bounds::kOrient2d * (absValue(detLeft) + absValue(detRight));
  if (det > bound)
    return 1;
  if (-det > bound)
    return -1;
  return orient2dExact(a[i], a[j], b[i], b[j], c[i], c[j]);
}

int insphereSoS(const TetMesh& mesh, VertexId a, VertexId b, VertexId c, VertexId d, VertexId e)
{
  return insphereSoSFiltered(mesh.coords.data(), a, b, c, d, e);
}

} // namespace predicates
} // namespace tetmesher
