// Exact predicates: the public entry points run the inline filters of FilteredPredicates.h;
// this file holds the exact fallbacks (expansion arithmetic) and the symbolic perturbation.
//
// The exact versions evaluate the same determinants as the filters, but every coordinate
// difference is kept as a two-component expansion (twoDiff is exact) and every product and
// sum as an expansion, so the sign is the sign of the exact real determinant.
#include "Predicates.h"

#include "BinaryParts.h"
#include "EpochHashTable.h"
#include "ExpansionArithmetic.h"
#include "FilteredPredicates.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <sstream>
#include <vector>

namespace tetmesher
{
namespace predicates
{

std::string coordinateRangeError(const double* points, std::int64_t pointCount, const char* noun)
{
  for (std::int64_t i = 0; i < 3 * pointCount; ++i)
  {
    const double c = points[i];
    if (inExactRange(c))
      continue;
    std::ostringstream error;
    error.precision(17);
    error << noun << " " << i / 3 << " has ";
    if (!std::isfinite(c))
      error << "a non-finite coordinate (" << c << ")";
    else
    {
      error << "coordinate " << c;
      error.precision(3);
      error << ", outside the magnitudes " << kMinExactCoordinate << " to " << kMaxExactCoordinate
            << " (and 0) where the predicates are exact; "
            << (std::abs(c) > 1 ? "scale the model down" : "set it to 0 or scale the model up");
    }
    return error.str();
  }
  return {};
}

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
// zero elimination keeps them to a handful, so the arena stays in cache. It starts small
// (32 KiB): zeroing a first 1 MiB took a third of a 24-triangle run of the command line;
// a predicate that needs more chains a block, and the arena grows to the sum afterwards.
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
  std::vector<double> storage = std::vector<double>(1u << 12);
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

// Second filter stage in x87 extended precision (64-bit significand on x86-64 Linux): the
// same evaluation and the same a-priori bound as the double filter, with eps = 2^-64. The
// inputs are doubles, so they convert exactly; the bound covers every rounding after that.
// Nearly co-spherical input (points on a sphere) fails the double filter constantly and is
// decided here at a fraction of the cost of expansion arithmetic. Returns 0 when uncertain.
// Where long double is no wider than double, the stage is skipped.
// The compiler's word is not enough: emulators run x87 code in double precision (valgrind
// does), where the 2^-64 bound would be wrong and the stage would decide signs falsely (a
// Delaunay build under valgrind failed with a vertex "that could not be inserted"). So the
// 64-bit significand is checked once at run time: 1 + 2^-63 must not round to 1.
bool extendedPrecisionHolds()
{
  static const bool holds = []
  {
    volatile long double one = 1.0L;
    volatile long double tiny = 1.0L / 9223372036854775808.0L; // 2^-63
    const long double sum = one + tiny;
    return sum - one == tiny;
  }();
  return holds;
}
const bool kHasExtendedStage =
  std::numeric_limits<long double>::digits >= 64 && extendedPrecisionHolds();
constexpr long double kEpsilonExtended = 1.0L / 18446744073709551616.0L; // 2^-64
constexpr long double kOrient3dExtendedBound = (7.0L + 56.0L * kEpsilonExtended) * kEpsilonExtended;
constexpr long double kInsphereExtendedBound =
  (16.0L + 224.0L * kEpsilonExtended) * kEpsilonExtended;

int orient3dExtended(const double* a, const double* b, const double* c, const double* d)
{
  using L = long double;
  const L adx = L(a[0]) - d[0], bdx = L(b[0]) - d[0], cdx = L(c[0]) - d[0];
  const L ady = L(a[1]) - d[1], bdy = L(b[1]) - d[1], cdy = L(c[1]) - d[1];
  const L adz = L(a[2]) - d[2], bdz = L(b[2]) - d[2], cdz = L(c[2]) - d[2];
  const L bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const L cdxady = cdx * ady, adxcdy = adx * cdy;
  const L adxbdy = adx * bdy, bdxady = bdx * ady;
  const L det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const L permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * std::fabs(adz) +
    (std::fabs(cdxady) + std::fabs(adxcdy)) * std::fabs(bdz) +
    (std::fabs(adxbdy) + std::fabs(bdxady)) * std::fabs(cdz);
  const L bound = kOrient3dExtendedBound * permanent;
  return det > bound ? 1 : (-det > bound ? -1 : 0);
}

int insphereExtended(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* e)
{
  using L = long double;
  const L aex = L(a[0]) - e[0], bex = L(b[0]) - e[0], cex = L(c[0]) - e[0], dex = L(d[0]) - e[0];
  const L aey = L(a[1]) - e[1], bey = L(b[1]) - e[1], cey = L(c[1]) - e[1], dey = L(d[1]) - e[1];
  const L aez = L(a[2]) - e[2], bez = L(b[2]) - e[2], cez = L(c[2]) - e[2], dez = L(d[2]) - e[2];
  const L aexbey = aex * bey, bexaey = bex * aey, bexcey = bex * cey, cexbey = cex * bey;
  const L cexdey = cex * dey, dexcey = dex * cey, dexaey = dex * aey, aexdey = aex * dey;
  const L aexcey = aex * cey, cexaey = cex * aey, bexdey = bex * dey, dexbey = dex * bey;
  const L ab = aexbey - bexaey, bc = bexcey - cexbey, cd = cexdey - dexcey;
  const L da = dexaey - aexdey, ac = aexcey - cexaey, bd = bexdey - dexbey;
  const L abc = aez * bc - bez * ac + cez * ab;
  const L bcd = bez * cd - cez * bd + dez * bc;
  const L cda = cez * da + dez * ac + aez * cd;
  const L dab = dez * ab + aez * bd + bez * da;
  const L alift = aex * aex + aey * aey + aez * aez;
  const L blift = bex * bex + bey * bey + bez * bez;
  const L clift = cex * cex + cey * cey + cez * cez;
  const L dlift = dex * dex + dey * dey + dez * dez;
  const L det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
  auto f = [](L x) { return std::fabs(x); };
  const L permanent = ((f(cexdey) + f(dexcey)) * f(bez) + (f(dexbey) + f(bexdey)) * f(cez) +
                        (f(bexcey) + f(cexbey)) * f(dez)) *
      alift +
    ((f(dexaey) + f(aexdey)) * f(cez) + (f(aexcey) + f(cexaey)) * f(dez) +
      (f(cexdey) + f(dexcey)) * f(aez)) *
      blift +
    ((f(aexbey) + f(bexaey)) * f(dez) + (f(bexdey) + f(dexbey)) * f(aez) +
      (f(dexaey) + f(aexdey)) * f(bez)) *
      clift +
    ((f(bexcey) + f(cexbey)) * f(aez) + (f(cexaey) + f(aexcey)) * f(bez) +
      (f(aexbey) + f(bexaey)) * f(cez)) *
      dlift;
  const L bound = kInsphereExtendedBound * permanent;
  return det > bound ? 1 : (-det > bound ? -1 : 0);
}

// Third stage, for exactly degenerate input on a lattice (grids, integer coordinates, or
// any coordinates whose differences are small multiples of a common power of two): if
// every coordinate difference is exact and, after an exact power-of-two scaling, an integer
// below 2^bits, then every intermediate value of the determinant is an integer below 2^63
// and a 64-bit integer evaluation is exact, zero included. Bits: insphere needs
// 72 * 2^(5 bits) < 2^63 (bits = 11; 24 with 128-bit integers); orient3d needs
// 6 * 2^(3 bits) < 2^63 (bits = 20). The scaling is by a positive power of two, which
// leaves the determinants' signs as they are.
constexpr int kMaxLatticeBits = 24;

// 2^e as a double, for |e| <= 1022 (a normal number: multiplying by it is exact unless the
// product leaves the normal range).
double powerOfTwo(int e)
{
  const std::uint64_t bits = static_cast<std::uint64_t>(1023 + e) << 52;
  double x;
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

// The differences points[i] - origin as integers, scaled by 2^-(the lowest bit set in any
// of them): returns the bits the largest then needs (every |out| < 2^bits; 0 when all are
// zero), or -1 when a difference is not exact in double. Past kMaxLatticeBits, out is not
// filled and the count is returned as soon as it is reached (a later difference may be inexact).
// The bit positions come from each double's exponent and significand, in one pass: the lattice's
// differences took 4% of a refinement run (fandisk at h = 0.0103) through frexp and ldexp, twice
// per in-sphere test (11 bits, then 24).
int integerDifferences(const double* const* points,
  int count,
  const double* origin,
  long long (*out)[3])
{
  double diff[5][3];
  int lowest = std::numeric_limits<int>::max(), highest = std::numeric_limits<int>::min();
  for (int i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k)
    {
      double x, y;
      twoDiff(points[i][k], origin[k], x, y);
      if (y != 0.0 || !std::isfinite(x)) // (a NaN tail fails the first test too)
        return -1;
      diff[i][k] = x;
      binaryParts(x, lowest, highest);
      // Points off any small lattice (most points in floating point) show it at the first
      // difference: 30-50 bits, then no need to look at the other 11.
      if (highest != std::numeric_limits<int>::min() && highest - lowest + 1 > kMaxLatticeBits)
        return highest - lowest + 1;
    }
  if (lowest == std::numeric_limits<int>::max())
  {
    for (int i = 0; i < count; ++i)
      for (int k = 0; k < 3; ++k)
        out[i][k] = 0;
    return 0;
  }
  const int needed = highest - lowest + 1;
  if (needed > kMaxLatticeBits)
    return needed;
  // 2^-lowest must be a normal double (|lowest| <= 1022) to scale by it exactly.
  if (lowest < -1022 || lowest > 1022)
    return -1;
  const double scale = powerOfTwo(-lowest);
  for (int i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k)
      out[i][k] = static_cast<long long>(diff[i][k] * scale);
  return needed;
}

// 0 when not applicable, else 1 + (sign + 1): decodes with decodeLattice.
int orient3dLattice(const double* a, const double* b, const double* c, const double* d)
{
  const double* const pts[3] = { a, b, c };
  long long m[3][3];
  const int bits = integerDifferences(pts, 3, d, m);
  if (bits < 0 || bits > 20)
    return 0;
  const long long det = m[0][2] * (m[1][0] * m[2][1] - m[2][0] * m[1][1]) +
    m[1][2] * (m[2][0] * m[0][1] - m[0][0] * m[2][1]) +
    m[2][2] * (m[0][0] * m[1][1] - m[1][0] * m[0][1]);
  return 2 + (det > 0) - (det < 0);
}

template<typename Int>
int signOf(Int x)
{
  return (x > 0) - (x < 0);
}

// The in-sphere determinant of integer differences m (rows a-e .. d-e), in an integer type
// wide enough for 72 * max|m|^5; on a zero, with `ids`, the perturbed answer.
template<typename Int>
int insphereOfIntegers(const long long (*m)[3], const VertexId* ids)
{
  auto x = [m](int i, int k) { return static_cast<Int>(m[i][k]); };
  const Int ab = x(0, 0) * x(1, 1) - x(1, 0) * x(0, 1);
  const Int bc = x(1, 0) * x(2, 1) - x(2, 0) * x(1, 1);
  const Int cd = x(2, 0) * x(3, 1) - x(3, 0) * x(2, 1);
  const Int da = x(3, 0) * x(0, 1) - x(0, 0) * x(3, 1);
  const Int ac = x(0, 0) * x(2, 1) - x(2, 0) * x(0, 1);
  const Int bd = x(1, 0) * x(3, 1) - x(3, 0) * x(1, 1);
  const Int abc = x(0, 2) * bc - x(1, 2) * ac + x(2, 2) * ab;
  const Int bcd = x(1, 2) * cd - x(2, 2) * bd + x(3, 2) * bc;
  const Int cda = x(2, 2) * da + x(3, 2) * ac + x(0, 2) * cd;
  const Int dab = x(3, 2) * ab + x(0, 2) * bd + x(1, 2) * da;
  Int lift[4];
  for (int i = 0; i < 4; ++i)
    lift[i] = x(i, 0) * x(i, 0) + x(i, 1) * x(i, 1) + x(i, 2) * x(i, 2);
  const Int det = (lift[3] * abc - lift[2] * dab) + (lift[1] * cda - lift[0] * bcd);
  if (det == 0 && ids)
    return 2 +
      tieBreakFromMinors(
        signOf(abc), signOf(bcd), signOf(cda), signOf(dab), signOf(abc - bcd + cda - dab), ids);
  return 2 + signOf(det);
}

int insphereLattice(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* e,
  const VertexId* ids)
{
  const double* const pts[4] = { a, b, c, d };
  long long m[4][3];
  const int bits = integerDifferences(pts, 4, e, m);
  if (bits < 0)
    return 0;
  if (bits <= 11)
    return insphereOfIntegers<long long>(m, ids);
#ifdef __SIZEOF_INT128__
  // 128 bits hold 72 * 2^(5 * 24): lattices with finer steps relative to their extent (the
  // refinement's snapped lattice: steps of a/4096 and more) stay out of the expansions.
  if (bits <= kMaxLatticeBits)
    return insphereOfIntegers<__int128>(m, ids);
#endif
  return 0;
}

#ifdef __SIZEOF_INT128__
// Fourth stage (insphere and orient3d): the coordinates themselves as integers. Points whose
// coordinates span at most 61 bits (from the highest bit of the largest to the lowest bit set
// in any) are, after scaling by a power of two, integers below 2^61: their differences are
// exact int64 values below 2^62, and the in-sphere determinant an integer below 2^317,
// evaluated exactly in 5 limbs of 64 bits; up to 125 bits, in twice the limbs. Points on a
// sphere computed in floating point (icosphere.vtp, uv_sphere.vtp: coordinates in [-1, 1])
// are nearly co-spherical beyond the extended stage's reach, and the expansions took ~25k
// instructions per test: the surface Delaunay of icosphere.vtp, 10k such tests, was 16% of a
// refinement run at h/2 (counted under valgrind, where the extended stage is off).

// Signed integers of N 64-bit limbs, two's complement, least significant limb first.
template<int N>
struct Wide
{
  std::uint64_t limb[N];
};

template<int N>
bool isNegative(const Wide<N>& a)
{
  return (a.limb[N - 1] >> 63) != 0;
}

// a + b, or a - b as a + ~b + 1: one carry chain for both; the bounds above keep every
// result far from overflow.
template<bool Subtract, int N>
Wide<N> carried(const Wide<N>& a, const Wide<N>& b)
{
  Wide<N> r;
  std::uint64_t carry = Subtract ? 1 : 0;
  for (int i = 0; i < N; ++i)
  {
    const std::uint64_t y = Subtract ? ~b.limb[i] : b.limb[i];
    const unsigned __int128 t = static_cast<unsigned __int128>(a.limb[i]) + y + carry;
    r.limb[i] = static_cast<std::uint64_t>(t);
    carry = static_cast<std::uint64_t>(t >> 64);
  }
  return r;
}
template<int N>
Wide<N> added(const Wide<N>& a, const Wide<N>& b)
{
  return carried<false>(a, b);
}
template<int N>
Wide<N> subtracted(const Wide<N>& a, const Wide<N>& b)
{
  return carried<true>(a, b);
}
template<int N>
Wide<N> negated(const Wide<N>& a)
{
  return subtracted(Wide<N>{}, a);
}

// The product of a (M limbs) and b (K limbs), M + K limbs: magnitudes by schoolbook.
template<int M, int K>
Wide<M + K> multiplied(const Wide<M>& a, const Wide<K>& b)
{
  const bool negative = isNegative(a) != isNegative(b);
  const Wide<M> x = isNegative(a) ? negated(a) : a;
  const Wide<K> y = isNegative(b) ? negated(b) : b;
  Wide<M + K> r;
  for (int i = 0; i < M + K; ++i)
    r.limb[i] = 0;
  for (int i = 0; i < M; ++i)
  {
    std::uint64_t carry = 0;
    for (int j = 0; j < K; ++j)
    {
      const unsigned __int128 t =
        static_cast<unsigned __int128>(x.limb[i]) * y.limb[j] + r.limb[i + j] + carry;
      r.limb[i + j] = static_cast<std::uint64_t>(t);
      carry = static_cast<std::uint64_t>(t >> 64);
    }
    r.limb[i + K] = carry;
  }
  return negative ? negated(r) : r;
}

// One limb by one: the processor's signed 64 x 64 -> 128-bit product.
Wide<2> multiplied(const Wide<1>& a, const Wide<1>& b)
{
  const __int128 p = static_cast<__int128>(static_cast<std::int64_t>(a.limb[0])) *
    static_cast<std::int64_t>(b.limb[0]);
  const unsigned __int128 u = static_cast<unsigned __int128>(p);
  return { { static_cast<std::uint64_t>(u), static_cast<std::uint64_t>(u >> 64) } };
}

template<int N>
int signOfWide(const Wide<N>& a)
{
  if (isNegative(a))
    return -1;
  for (int i = 0; i < N; ++i)
    if (a.limb[i] != 0)
      return 1;
  return 0;
}

// The points' coordinates scaled by one power of two to integers below 2^(64 L - 3), as
// differences from the last point (below 2^(64 L - 2)) in L limbs: L = 1 when the 15
// coordinates span at most 61 bits, 2 up to 125 (a coordinate of 1e-17 among ones near 1,
// as cos(pi/2) gives on a UV sphere: ~106 bits). 0 when they span more or are not finite.
int scaledDifferences(const double* const* points, int count, Wide<2> (*out)[3])
{
  int lowest = std::numeric_limits<int>::max(), highest = std::numeric_limits<int>::min();
  std::uint64_t significand[5][3];
  int exponent[5][3];
  for (int i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k)
    {
      const double x = points[i][k];
      if (!std::isfinite(x))
        return 0;
      const BinaryParts parts = binaryParts(x, lowest, highest);
      significand[i][k] = parts.significand;
      exponent[i][k] = parts.exponent;
    }
  if (lowest == std::numeric_limits<int>::max())
    lowest = highest = 0; // all zero
  const int span = highest - lowest + 1;
  if (span > 125)
    return 0;
  if (span <= 61 && lowest >= -1022 && lowest <= 1022)
  {
    // Within one limb: scaling by 2^-lowest (a normal double) is exact, and so is the
    // conversion of the integer it gives, below 2^61.
    const double scale = powerOfTwo(-lowest);
    long long v[5][3];
    for (int i = 0; i < count; ++i)
      for (int k = 0; k < 3; ++k)
        v[i][k] = static_cast<long long>(points[i][k] * scale);
    for (int i = 0; i + 1 < count; ++i)
      for (int k = 0; k < 3; ++k)
      {
        const long long d = v[i][k] - v[count - 1][k]; // below 2^62
        out[i][k] = { { static_cast<std::uint64_t>(d), d < 0 ? ~std::uint64_t(0) : 0 } };
      }
    return 1;
  }
  __int128 v[5][3];
  for (int i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k)
    {
      // m 2^(exponent - lowest), exponent - lowest in [0, span - 1]: below 2^125.
      const std::uint64_t m = significand[i][k];
      const int shift = exponent[i][k] - lowest;
      const unsigned __int128 magnitude = m == 0
        ? 0
        : (shift >= 0 ? static_cast<unsigned __int128>(m) << shift
                      : static_cast<unsigned __int128>(m >> -shift));
      v[i][k] = std::signbit(points[i][k]) ? -static_cast<__int128>(magnitude)
                                           : static_cast<__int128>(magnitude);
    }
  for (int i = 0; i + 1 < count; ++i)
    for (int k = 0; k < 3; ++k)
    {
      const unsigned __int128 d = static_cast<unsigned __int128>(v[i][k] - v[count - 1][k]);
      out[i][k] = { { static_cast<std::uint64_t>(d), static_cast<std::uint64_t>(d >> 64) } };
    }
  return span <= 61 ? 1 : 2;
}

// The low limb of x (a Wide<2> whose value fits one limb), as Wide<1>.
Wide<1> low(const Wide<2>& x)
{
  return { { x.limb[0] } };
}

// The in-sphere determinant's sign from differences of L limbs (|.| < 2^(64 L - 2)): minors
// below 2^(128 L - 3) in 2L limbs, cofactors below 2^(192 L - 3) in 3L, lifts below
// 2^(128 L - 2) in 2L, the determinant below 2^(320 L - 1) in 5L. As insphereOfIntegers.
template<int L>
int insphereOfWide(const Wide<L> (&x)[4][3], const VertexId* ids)
{
  auto minor = [&x](int i, int j) // x_i y_j - x_j y_i
  { return subtracted(multiplied(x[i][0], x[j][1]), multiplied(x[j][0], x[i][1])); };
  using Minor = Wide<2 * L>;
  const Minor ab = minor(0, 1), bc = minor(1, 2), cd = minor(2, 3);
  const Minor da = minor(3, 0), ac = minor(0, 2), bd = minor(1, 3);
  const Wide<3 * L> abc =
    added(subtracted(multiplied(x[0][2], bc), multiplied(x[1][2], ac)), multiplied(x[2][2], ab));
  const Wide<3 * L> bcd =
    added(subtracted(multiplied(x[1][2], cd), multiplied(x[2][2], bd)), multiplied(x[3][2], bc));
  const Wide<3 * L> cda =
    added(added(multiplied(x[2][2], da), multiplied(x[3][2], ac)), multiplied(x[0][2], cd));
  const Wide<3 * L> dab =
    added(added(multiplied(x[3][2], ab), multiplied(x[0][2], bd)), multiplied(x[1][2], da));
  Wide<2 * L> lift[4];
  for (int i = 0; i < 4; ++i)
    lift[i] = added(added(multiplied(x[i][0], x[i][0]), multiplied(x[i][1], x[i][1])),
      multiplied(x[i][2], x[i][2]));
  const Wide<5 * L> det = added(subtracted(multiplied(lift[3], abc), multiplied(lift[2], dab)),
    subtracted(multiplied(lift[1], cda), multiplied(lift[0], bcd)));
  const int s = signOfWide(det);
  if (s != 0 || !ids)
    return s;
  // Each minor is below 2^(192 L - 3) in magnitude, so abc - bcd + cda - dab stays below
  // 2^(192 L - 1) and fits the 3L limbs.
  const Wide<3 * L> abcd = added(subtracted(abc, bcd), subtracted(cda, dab));
  return tieBreakFromMinors(
    signOfWide(abc), signOfWide(bcd), signOfWide(cda), signOfWide(dab), signOfWide(abcd), ids);
}

// The orientation's sign from differences of L limbs: the determinant below 2^(192 L - 3).
template<int L>
int orient3dOfWide(const Wide<L> (&x)[3][3])
{
  auto minor = [&x](int i, int j) // x_i y_j - x_j y_i
  { return subtracted(multiplied(x[i][0], x[j][1]), multiplied(x[j][0], x[i][1])); };
  // adz*(bdx*cdy - cdx*bdy) + bdz*(cdx*ady - adx*cdy) + cdz*(adx*bdy - bdx*ady)
  const Wide<3 * L> det =
    added(added(multiplied(x[0][2], minor(1, 2)), multiplied(x[1][2], minor(2, 0))),
      multiplied(x[2][2], minor(0, 1)));
  return signOfWide(det);
}

// The sign that `sign` gives on the points' differences from the last one (Rows of them),
// in one limb when they fit, else in two; as insphereLattice codes it: 0 when not applicable
// (the points span too many bits), else 1 + (sign + 1).
template<int Rows, typename Sign>
int wideSign(const double* const* points, const Sign& sign)
{
  Wide<2> x[Rows][3];
  const int limbs = scaledDifferences(points, Rows + 1, x);
  if (limbs == 1)
  {
    Wide<1> y[Rows][3];
    for (int i = 0; i < Rows; ++i)
      for (int k = 0; k < 3; ++k)
        y[i][k] = low(x[i][k]);
    return 2 + sign(y);
  }
  return limbs == 2 ? 2 + sign(x) : 0;
}

int insphereWide(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* e,
  const VertexId* ids)
{
  const double* const points[5] = { a, b, c, d, e };
  return wideSign<4>(points, [ids](const auto& x) { return insphereOfWide(x, ids); });
}

// The same for orient3d. CAD surfaces' nearly coplanar points whose differences are not
// exact in double otherwise go to the expansions.
int orient3dWide(const double* a, const double* b, const double* c, const double* d)
{
  const double* const points[4] = { a, b, c, d };
  return wideSign<3>(points, [](const auto& x) { return orient3dOfWide(x); });
}
#else
int insphereWide(const double*,
  const double*,
  const double*,
  const double*,
  const double*,
  const VertexId*)
{
  return 0;
}
int orient3dWide(const double*, const double*, const double*, const double*)
{
  return 0;
}
#endif

inline int decodeLattice(int code)
{
  return code - 2;
}

// An expansion of the two-product x*y (at most 2 components, zeros dropped).
int productExpansion(double x, double y, double* h)
{
  double p, e;
  twoProduct(x, y, p, e);
  int n = 0;
  if (e != 0.0)
    h[n++] = e;
  if (p != 0.0)
    h[n++] = p;
  return n;
}

// x1*y2 - x2*y1 exactly (at most 4 components).
int minorExpansion(double x1, double y2, double x2, double y1, double* h)
{
  double left[2], right[2];
  const int nl = productExpansion(x1, y2, left), nr = productExpansion(x2, y1, right);
  return diffExpansions(nl, left, nr, right, h);
}

// Fourth stage, when every coordinate difference is exact in double (nearby points, as on the
// planar faces of CAD parts, where the exact zeros are): the determinant in expansions on
// the stack, two-products for the minors (4 components), scaled (8) and summed (24), without
// the arena. 2 when a difference is not exact, else the sign.
int orient3dOfExactDifferences(const double* a, const double* b, const double* c, const double* d)
{
  double m[3][3];
  const double* const rows[3] = { a, b, c };
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
    {
      double tail;
      twoDiff(rows[i][k], d[k], m[i][k], tail);
      if (tail != 0.0)
        return 2;
    }
  // adz*(bdx*cdy - cdx*bdy) + bdz*(cdx*ady - adx*cdy) + cdz*(adx*bdy - bdx*ady)
  double minor[4], t1[8], t2[8], t3[8], t12[16], all[24];
  int n = minorExpansion(m[1][0], m[2][1], m[2][0], m[1][1], minor);
  const int n1 = scaleExpansion(n, minor, m[0][2], t1);
  n = minorExpansion(m[2][0], m[0][1], m[0][0], m[2][1], minor);
  const int n2 = scaleExpansion(n, minor, m[1][2], t2);
  n = minorExpansion(m[0][0], m[1][1], m[1][0], m[0][1], minor);
  const int n3 = scaleExpansion(n, minor, m[2][2], t3);
  const int n12 = sumExpansions(n1, t1, n2, t2, t12);
  return expansionSign(sumExpansions(n12, t12, n3, t3, all), all);
}

} // namespace

namespace
{

// The exact stages below, on (a, b, c, d) as given.
int orient3dExactStages(const double* a, const double* b, const double* c, const double* d)
{
  if (const int code = orient3dLattice(a, b, c, d))
    return decodeLattice(code);
  if (kHasExtendedStage)
  {
    const int s = orient3dExtended(a, b, c, d);
    if (s != 0)
      return s;
  }
  if (const int code = orient3dWide(a, b, c, d))
    return decodeLattice(code);
  if (const int s = orient3dOfExactDifferences(a, b, c, d); s != 2)
    return s;
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

// A memo of the exact stages' answers, keyed by the four points' coordinates: the flips of
// boundary recovery, flat-tet and Steiner removal ask the same nearly or exactly coplanar
// quadruples again and again (gear.vtp's boundary mesh: 62k exact calls on 15k point sets,
// helix_tube's 121k on 21k), each ~670 instructions. The points are sorted lexicographically
// and the sign of the sorted order is stored; the answer is that sign times the permutation's
// parity, so any order of the same points hits. Keyed by values, not ids, it holds across
// meshes and calls; one table per thread, direct-mapped (a collision evicts), made on the
// first exact call.
class Orient3dMemo
{
public:
  int sign(const double* a, const double* b, const double* c, const double* d)
  {
    const double* p[4] = { a, b, c, d };
    // Sorting network for 4 (5 compare-exchanges); each exchange flips the parity.
    bool odd = false;
    auto exchange = [&](int i, int j)
    {
      if (less(p[j], p[i]))
      {
        std::swap(p[i], p[j]);
        odd = !odd;
      }
    };
    exchange(0, 1);
    exchange(2, 3);
    exchange(0, 2);
    exchange(1, 3);
    exchange(1, 2);
    double key[12];
    for (int k = 0; k < 4; ++k)
      std::memcpy(key + 3 * k, p[k], 3 * sizeof(double));
    // The coordinates' bits folded, then mixed once.
    std::uint64_t h = 0;
    for (double x : key)
    {
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      h = (h ^ bits) * 0x9e3779b97f4a7c15ull;
    }
    h = MixHash64{}(h);
    if (!slots_)
    {
      // Left uninitialised (a large allocation maps zero pages lazily): a small run that asks
      // a few exact questions touches a few pages, not the whole table.
      slots_.reset(new Entry[kSlots]);
      used_.assign(kSlots / 64, 0);
    }
    const std::size_t i = h & (kSlots - 1);
    Entry& slot = slots_[i];
    std::uint64_t& word = used_[i / 64];
    const std::uint64_t bit = std::uint64_t{ 1 } << (i % 64);
    if (!((word & bit) && std::memcmp(slot.coords, key, sizeof key) == 0))
    {
      std::memcpy(slot.coords, key, sizeof key);
      slot.sign = static_cast<std::int8_t>(orient3dExactStages(p[0], p[1], p[2], p[3]));
      word |= bit;
    }
    return odd ? -slot.sign : slot.sign;
  }

private:
  static bool less(const double* x, const double* y)
  {
    return x[0] != y[0] ? x[0] < y[0] : x[1] != y[1] ? x[1] < y[1] : x[2] < y[2];
  }
  struct Entry // trivial: new Entry[n] leaves it uninitialised
  {
    double coords[12];
    std::int8_t sign;
  };
  static constexpr std::size_t kSlots = 4096;
  std::unique_ptr<Entry[]> slots_;
  std::vector<std::uint64_t> used_; // a bit per slot: written
};

} // namespace

int orient3dExact(const double* a, const double* b, const double* c, const double* d)
{
  thread_local Orient3dMemo memo;
  return memo.sign(a, b, c, d);
}

namespace
{

// insphereExact; with `ids`, an exact zero found by the integer stages (lattice, wide) is
// answered by the symbolic perturbation from their own minors (tieBreakFromMinors), and only
// the expansions' zero is left to the caller's tie break.
int insphereExactStages(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* e,
  const VertexId* ids)
{
  if (const int code = insphereLattice(a, b, c, d, e, ids))
    return decodeLattice(code);
  if (kHasExtendedStage)
  {
    const int s = insphereExtended(a, b, c, d, e);
    if (s != 0)
      return s;
  }
  if (const int code = insphereWide(a, b, c, d, e, ids))
    return decodeLattice(code);
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

} // namespace

int insphereExact(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* e)
{
  return insphereExactStages(a, b, c, d, e, nullptr);
}

int insphereExactSoS(const double* const points[5], const VertexId ids[5])
{
  const int s = insphereExactStages(points[0], points[1], points[2], points[3], points[4], ids);
  return s != 0 ? s : insphereTieBreak(points, ids);
}

int orient2dExact(double ax, double ay, double bx, double by, double cx, double cy)
{
  {
    // Exact differences (the common case): the minor by two-products, on the stack.
    double acx, acy, bcx, bcy, t1, t2, t3, t4;
    twoDiff(ax, cx, acx, t1);
    twoDiff(ay, cy, acy, t2);
    twoDiff(bx, cx, bcx, t3);
    twoDiff(by, cy, bcy, t4);
    if (t1 == 0.0 && t2 == 0.0 && t3 == 0.0 && t4 == 0.0)
    {
      double minor[4];
      return expansionSign(minorExpansion(acx, bcy, acy, bcx, minor), minor);
    }
  }
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
