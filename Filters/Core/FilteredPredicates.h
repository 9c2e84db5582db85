// Inline floating-point filters for the exact predicates of Predicates.h, for hot loops.
//
// Each function evaluates the determinant in double precision and compares it with a
// proven bound on the rounding error (Shewchuk 1997, the "A" bounds: the determinant is
// evaluated from coordinate differences, and the bound is a constant times the permanent,
// i.e. the same expression with every term replaced by its absolute value). When the
// magnitude of the determinant exceeds the bound, its sign is certainly right; otherwise
// the exact expansion-arithmetic version decides. No epsilon ever decides a sign.
#pragma once

#include "TetMesh.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace tetmesher
{
namespace predicates
{

// Exact (slow-path) evaluations; defined in Predicates.cxx.
int orient3dExact(const double* a, const double* b, const double* c, const double* d);
int insphereExact(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* e);
int orient2dExact(double ax, double ay, double bx, double by, double cx, double cy);
// Symbolic-perturbation tie break, called only when insphere is exactly zero.
int insphereTieBreak(const double* const points[5], const VertexId ids[5]);
// The exact stages of insphere with the symbolic perturbation (never 0 for a positively
// oriented points[0..3]): insphereExact, then on a zero insphereTieBreak, except that the
// integer stages answer their own zeros from the determinant's minors.
int insphereExactSoS(const double* const points[5], const VertexId ids[5]);

// The symbolic perturbation's answer (insphereTieBreak) when the in-sphere determinant of
// (a,b,c,d,e) is exactly zero, from the exact signs of the orientations its lift cofactors
// are made of: abc = orient3d(a,b,c,e), bcd = orient3d(b,c,d,e), cda = orient3d(c,d,a,e),
// dab = orient3d(d,a,b,e) (the 3x3 minors of the differences from e) and abcd =
// orient3d(a,b,c,d) = abc - bcd + cda - dab. Replacing point k by e gives C_0 = -bcd,
// C_1 = cda, C_2 = -dab, C_3 = abc, and C_4 = -abcd; the first non-zero one by decreasing id
// decides (0 only for a flat a,b,c,d). For the stages that hold those minors exactly.
// T: int for the minors' signs, or double where the minors themselves are exact.
template<typename T>
int tieBreakFromMinors(T abc, T bcd, T cda, T dab, T abcd, const VertexId ids[5])
{
  const T cofactor[5] = { -bcd, cda, -dab, abc, -abcd };
  unsigned taken = 0;
  for (int step = 0; step < 5; ++step)
  {
    int k = -1;
    for (int i = 0; i < 5; ++i)
      if (!((taken >> i) & 1u) && (k < 0 || ids[i] > ids[k]))
        k = i;
    taken |= 1u << k;
    if (cofactor[k] != 0)
      return cofactor[k] > 0 ? 1 : -1;
  }
  return 0;
}

namespace bounds
{
constexpr double kEpsilon = 1.1102230246251565e-16; // 2^-53, half an ulp of 1
constexpr double kOrient2d = (3.0 + 16.0 * kEpsilon) * kEpsilon;
constexpr double kOrient3d = (7.0 + 56.0 * kEpsilon) * kEpsilon;
constexpr double kInsphere = (16.0 + 224.0 * kEpsilon) * kEpsilon;
}

// std::fabs compiles to a bit mask (andpd); a ternary compiles to compare-and-branch, which
// mispredicts constantly on random signs.
inline double absValue(double x)
{
  return std::fabs(x);
}

// The sign of a nonzero x from its sign bit: the compiler turns a comparison back into a
// branch, which on random signs mispredicts half the time.
inline int signOfNonzero(double x)
{
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return 1 - 2 * static_cast<int>(bits >> 63);
}

inline int orient3dFiltered(const double* a, const double* b, const double* c, const double* d)
{
  const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  const double adz = a[2] - d[2], bdz = b[2] - d[2], cdz = c[2] - d[2];
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (absValue(bdxcdy) + absValue(cdxbdy)) * absValue(adz) +
    (absValue(cdxady) + absValue(adxcdy)) * absValue(bdz) +
    (absValue(adxbdy) + absValue(bdxady)) * absValue(cdz);
  const double bound = bounds::kOrient3d * permanent;
  if (det > bound)
    return 1;
  if (-det > bound)
    return -1;
  return orient3dExact(a, b, c, d);
}

// The in-sphere determinant of (a, b, c, d, e) as Shewchuk's filter evaluates it (differences
// from e, the 2x2 minors of x and y, the cofactors of the lift column, the lifts), and its
// permanent (the same expression with every term in magnitude), one double operation at a time.
// insphereTerms performs these very operations, four at a time; this one is the reference that
// tests hold it to, and the evaluation where the compiler has no vector extensions.
struct InsphereTerms
{
  double det;
  double permanent;
  // The cofactors of the lift column, abc, bcd, cda and dab (the 3x3 minors of the
  // differences; see tieBreakFromMinors), for the stages that hold them exactly.
  double cofactor[4];
};
inline InsphereTerms insphereTermsScalar(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* e)
{
  const double aex = a[0] - e[0], bex = b[0] - e[0], cex = c[0] - e[0], dex = d[0] - e[0];
  const double aey = a[1] - e[1], bey = b[1] - e[1], cey = c[1] - e[1], dey = d[1] - e[1];
  const double aez = a[2] - e[2], bez = b[2] - e[2], cez = c[2] - e[2], dez = d[2] - e[2];

  const double aexbey = aex * bey, bexaey = bex * aey;
  const double bexcey = bex * cey, cexbey = cex * bey;
  const double cexdey = cex * dey, dexcey = dex * cey;
  const double dexaey = dex * aey, aexdey = aex * dey;
  const double aexcey = aex * cey, cexaey = cex * aey;
  const double bexdey = bex * dey, dexbey = dex * bey;
  const double ab = aexbey - bexaey, bc = bexcey - cexbey, cd = cexdey - dexcey;
  const double da = dexaey - aexdey, ac = aexcey - cexaey, bd = bexdey - dexbey;

  const double abc = aez * bc - bez * ac + cez * ab;
  const double bcd = bez * cd - cez * bd + dez * bc;
  const double cda = cez * da + dez * ac + aez * cd;
  const double dab = dez * ab + aez * bd + bez * da;

  const double alift = aex * aex + aey * aey + aez * aez;
  const double blift = bex * bex + bey * bey + bez * bez;
  const double clift = cex * cex + cey * cey + cez * cez;
  const double dlift = dex * dex + dey * dey + dez * dez;

  const double det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);

  const double aezp = absValue(aez), bezp = absValue(bez), cezp = absValue(cez),
               dezp = absValue(dez);
  const double aexbeyp = absValue(aexbey), bexaeyp = absValue(bexaey);
  const double bexceyp = absValue(bexcey), cexbeyp = absValue(cexbey);
  const double cexdeyp = absValue(cexdey), dexceyp = absValue(dexcey);
  const double dexaeyp = absValue(dexaey), aexdeyp = absValue(aexdey);
  const double aexceyp = absValue(aexcey), cexaeyp = absValue(cexaey);
  const double bexdeyp = absValue(bexdey), dexbeyp = absValue(dexbey);
  const double permanent =
    ((cexdeyp + dexceyp) * bezp + (dexbeyp + bexdeyp) * cezp + (bexceyp + cexbeyp) * dezp) * alift +
    ((dexaeyp + aexdeyp) * cezp + (aexceyp + cexaeyp) * dezp + (cexdeyp + dexceyp) * aezp) * blift +
    ((aexbeyp + bexaeyp) * dezp + (bexdeyp + dexbeyp) * aezp + (dexaeyp + aexdeyp) * bezp) * clift +
    ((bexceyp + cexbeyp) * aezp + (cexaeyp + aexceyp) * bezp + (aexbeyp + bexaeyp) * cezp) * dlift;
  return { det, permanent, { abc, bcd, cda, dab } };
}

#if defined(__clang__) || (defined(__GNUC__) && __GNUC__ >= 12)
// insphereTermsScalar's operations in lanes (a, b, c, d): each lane performs, in the same
// order, the operations the scalar code performs for that point, so det and the permanent are
// the same doubles (TestPredicates checks it), but for a zero's sign, which no comparison
// sees: a zero minor negated by the lanes stays +0, and -0 - 0 is -0 where -0 + 0 is +0. Rotating
// the lanes pairs each point with the next (minors ab, bc, cd, da) and the one after (ac, bd, and
// their negations, which rounding leaves exact). The in-sphere test is the Delaunay kernel's
// innermost work: one thread inserting 1M uniform points, 3.2-3.4 s -> 2.9-3.05 s. Without AVX (the
// default target) each vector is two SSE2 registers.
inline InsphereTerms insphereTerms(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* e)
{
  typedef double Lanes __attribute__((vector_size(32)));
  typedef long long Bits __attribute__((vector_size(32)));
#define TETMESHER_NEXT(v) __builtin_shufflevector(v, v, 1, 2, 3, 0)
#define TETMESHER_SECOND(v) __builtin_shufflevector(v, v, 2, 3, 0, 1)
#define TETMESHER_PREVIOUS(v) __builtin_shufflevector(v, v, 3, 0, 1, 2)
  constexpr long long kMagnitude = 0x7fffffffffffffffLL; // |x|: the sign bit cleared
  const Bits magnitude = { kMagnitude, kMagnitude, kMagnitude, kMagnitude };
  const Lanes x = Lanes{ a[0], b[0], c[0], d[0] } - e[0];
  const Lanes y = Lanes{ a[1], b[1], c[1], d[1] } - e[1];
  const Lanes z = Lanes{ a[2], b[2], c[2], d[2] } - e[2];
  // aexbey, bexcey, cexdey, dexaey and bexaey, cexbey, dexcey, aexdey: minors ab, bc, cd, da.
  const Lanes xNextY = x * TETMESHER_NEXT(y), nextXY = TETMESHER_NEXT(x) * y;
  // aexcey, bexdey, cexaey, dexbey and cexaey, dexbey, aexcey, bexdey: ac, bd, -ac, -bd.
  const Lanes xSecondY = x * TETMESHER_SECOND(y), secondXY = TETMESHER_SECOND(x) * y;
  const Lanes minorNext = xNextY - nextXY, minorSecond = xSecondY - secondXY;
  // abc, bcd, cda, dab: e.g. aez*bc - bez*ac + cez*ab and cez*da - dez*(-ac) + aez*cd.
  const Lanes cofactor = (z * TETMESHER_NEXT(minorNext) - TETMESHER_NEXT(z) * minorSecond) +
    TETMESHER_SECOND(z) * minorNext;
  const Lanes lift = (x * x + y * y) + z * z;
  // dlift*abc, alift*bcd, blift*cda, clift*dab.
  const Lanes terms = TETMESHER_PREVIOUS(lift) * cofactor;
  const double det = (terms[0] - terms[3]) + (terms[2] - terms[1]);
  // The permanent: each lift times the sum of its cofactor's terms in magnitude.
  const Lanes sumNext = Lanes(Bits(xNextY) & magnitude) + Lanes(Bits(nextXY) & magnitude);
  const Lanes sumSecond = Lanes(Bits(xSecondY) & magnitude) + Lanes(Bits(secondXY) & magnitude);
  const Lanes zAbs = Lanes(Bits(z) & magnitude);
  const Lanes weight = (TETMESHER_SECOND(sumNext) * TETMESHER_NEXT(zAbs) +
                         TETMESHER_NEXT(sumSecond) * TETMESHER_SECOND(zAbs)) +
    TETMESHER_NEXT(sumNext) * TETMESHER_PREVIOUS(zAbs);
  const Lanes weighted = weight * lift;
  const double permanent = ((weighted[0] + weighted[1]) + weighted[2]) + weighted[3];
#undef TETMESHER_NEXT
#undef TETMESHER_SECOND
#undef TETMESHER_PREVIOUS
  return { det, permanent, { cofactor[0], cofactor[1], cofactor[2], cofactor[3] } };
}
#else
inline InsphereTerms insphereTerms(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* e)
{
  return insphereTermsScalar(a, b, c, d, e);
}
#endif

// The in-sphere filter alone: the sign where the filter decides it, else kUndecided.
constexpr int kUndecided = 2;
inline int insphereFilterSign(const InsphereTerms& terms)
{
  const double bound = bounds::kInsphere * terms.permanent;
  // One predictable branch (decided or not), and the sign without one: it is a coin flip in
  // the Delaunay kernel's cavity growth. |det| > bound >= 0, so det is not zero.
  if (absValue(terms.det) > bound)
    return signOfNonzero(terms.det);
  return kUndecided;
}

inline int insphereFilter(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* e)
{
  return insphereFilterSign(insphereTerms(a, b, c, d, e));
}

inline int insphereFiltered(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* e)
{
  const int s = insphereFilter(a, b, c, d, e);
  return s != kUndecided ? s : insphereExact(a, b, c, d, e);
}

// insphereSoS on raw coordinates (coords = mesh.coords.data()), for hot loops.
// `perturbationIds`, when given, maps the ids used here to the ids that define the symbolic
// perturbation (the Delaunay builder works on a renumbered copy of the points but must
// perturb by the caller's ids); nullptr means the ids themselves.
inline int insphereSoSFiltered(const double* coords,
  VertexId a,
  VertexId b,
  VertexId c,
  VertexId d,
  VertexId e,
  const VertexId* perturbationIds = nullptr)
{
  const double* pa = coords + 3 * static_cast<std::size_t>(a);
  const double* pb = coords + 3 * static_cast<std::size_t>(b);
  const double* pc = coords + 3 * static_cast<std::size_t>(c);
  const double* pd = coords + 3 * static_cast<std::size_t>(d);
  const double* pe = coords + 3 * static_cast<std::size_t>(e);
  const int s = insphereFilter(pa, pb, pc, pd, pe);
  if (s != kUndecided)
    return s;
  const double* const points[5] = { pa, pb, pc, pd, pe };
  if (perturbationIds)
  {
    const VertexId ids[5] = { perturbationIds[a],
      perturbationIds[b],
      perturbationIds[c],
      perturbationIds[d],
      perturbationIds[e] };
    return insphereExactSoS(points, ids);
  }
  const VertexId ids[5] = { a, b, c, d, e };
  return insphereExactSoS(points, ids);
}

} // namespace predicates
} // namespace tetmesher
