// Exact floating-point expansion arithmetic (Priest 1991, Shewchuk 1997, "Adaptive Precision
// Floating-Point Arithmetic and Fast Robust Geometric Predicates").
//
// An expansion is a sum of doubles x_0 + x_1 + ... + x_{n-1}, stored in order of increasing
// magnitude, whose components do not overlap; its value is exact and its sign is the sign of
// its largest (last non-zero) component. The primitives below compute sums and products of
// doubles with no rounding error by returning the rounded result plus its exact error term.
//
// Requirements: IEEE-754 double arithmetic with round-to-nearest-even and no extended
// precision or fused multiply-add contraction (the core is compiled with -ffp-contract=off;
// x86-64 uses SSE2, never x87).
#pragma once

namespace tetmesher
{
namespace expansion
{

// x + y == a + b exactly, x = fl(a + b). Requires |a| >= |b| (or a == 0).
inline void fastTwoSum(double a, double b, double& x, double& y)
{
  x = a + b;
  double bVirtual = x - a;
  y = b - bVirtual;
}

// x + y == a + b exactly, x = fl(a + b), for any a, b (Knuth's branch-free two-sum).
inline void twoSum(double a, double b, double& x, double& y)
{
  x = a + b;
  double bVirtual = x - a;
  double aVirtual = x - bVirtual;
  double bRoundoff = b - bVirtual;
  double aRoundoff = a - aVirtual;
  y = aRoundoff + bRoundoff;
}

// x + y == a - b exactly.
inline void twoDiff(double a, double b, double& x, double& y)
{
  x = a - b;
  double bVirtual = a - x;
  double aVirtual = x + bVirtual;
  double bRoundoff = bVirtual - b;
  double aRoundoff = a - aVirtual;
  y = aRoundoff + bRoundoff;
}

// Veltkamp/Dekker split: a == hi + lo, each with at most 26 significant bits, so that
// products of halves are exact.
inline void split(double a, double& hi, double& lo)
{
  constexpr double kSplitter = 134217729.0; // 2^27 + 1
  double c = kSplitter * a;
  double aBig = c - a;
  hi = c - aBig;
  lo = a - hi;
}

// x + y == a * b exactly, x = fl(a * b) (Dekker's two-product).
inline void twoProduct(double a, double b, double& x, double& y)
{
  x = a * b;
  double aHi, aLo, bHi, bLo;
  split(a, aHi, aLo);
  split(b, bHi, bLo);
  double err1 = x - aHi * bHi;
  double err2 = err1 - aLo * bHi;
  double err3 = err2 - aHi * bLo;
  y = aLo * bLo - err3;
}

// h = e * b. e has elen components; h needs room for 2*elen. Zero components are dropped.
// Returns the length of h.
int scaleExpansion(int elen, const double* e, double b, double* h);

// h = e + f (both non-overlapping, increasing magnitude). h needs room for elen + flen.
// Zero components are dropped. Returns the length of h.
int sumExpansions(int elen, const double* e, int flen, const double* f, double* h);

// h = e - f. Same contract as sumExpansions; f is negated on the fly.
int diffExpansions(int elen, const double* e, int flen, const double* f, double* h);

// h = e * f. h needs room for 2*elen*flen; scratch needs room for 4*elen*flen.
// Returns the length of h.
int multiplyExpansions(int elen,
  const double* e,
  int flen,
  const double* f,
  double* h,
  double* scratch);

// Sign of the value of an expansion: the sign of its largest component.
inline int expansionSign(int elen, const double* e)
{
  for (int i = elen - 1; i >= 0; --i)
  {
    if (e[i] > 0)
      return 1;
    if (e[i] < 0)
      return -1;
  }
  return 0;
}

} // namespace expansion
} // namespace tetmesher
