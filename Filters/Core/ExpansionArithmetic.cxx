// Expansion sums and products, written from the algorithms in Shewchuk (1997), section 2:
// SCALE-EXPANSION (Theorem 19) and FAST-EXPANSION-SUM (Theorem 13), both with zero
// elimination so that the expansions of near-degenerate input stay short.
#include "ExpansionArithmetic.h"

namespace tetmesher
{
namespace expansion
{

int scaleExpansion(int elen, const double* e, double b, double* h)
{
  if (elen == 0 || b == 0.0)
    return 0;
  int hlen = 0;
  double q, hh;
  twoProduct(e[0], b, q, hh);
  if (hh != 0.0)
    h[hlen++] = hh;
  for (int i = 1; i < elen; ++i)
  {
    double product, productErr;
    twoProduct(e[i], b, product, productErr);
    double sum;
    twoSum(q, productErr, sum, hh);
    if (hh != 0.0)
      h[hlen++] = hh;
    fastTwoSum(product, sum, q, hh);
    if (hh != 0.0)
      h[hlen++] = hh;
  }
  if (q != 0.0 || hlen == 0)
    h[hlen++] = q;
  return hlen;
}

namespace
{

// Merges e and f (optionally negating f) by increasing magnitude, accumulating with
// two-sum so that the result is non-overlapping. The merge order is what makes the
// fast (branch-light) variant correct under round-to-even.
template<bool NegateF>
int mergeSum(int elen, const double* e, int flen, const double* f, double* h)
{
  auto fAt = [f](int k) { return NegateF ? -f[k] : f[k]; };
  if (elen == 0 && flen == 0)
    return 0;
  if (elen == 0)
  {
    for (int k = 0; k < flen; ++k)
      h[k] = fAt(k);
    return flen;
  }
  if (flen == 0)
  {
    for (int k = 0; k < elen; ++k)
      h[k] = e[k];
    return elen;
  }
  int ei = 0, fi = 0;
  double enow = e[0], fnow = fAt(0);
  double q;
  if ((fnow > enow) == (fnow > -enow))
  {
    q = enow;
    enow = ++ei < elen ? e[ei] : 0.0;
  }
  else
  {
    q = fnow;
    fnow = ++fi < flen ? fAt(fi) : 0.0;
  }
  int hlen = 0;
  double qNew, hh;
  if (ei < elen && fi < flen)
  {
    if ((fnow > enow) == (fnow > -enow))
    {
      fastTwoSum(enow, q, qNew, hh);
      enow = ++ei < elen ? e[ei] : 0.0;
    }
    else
    {
      fastTwoSum(fnow, q, qNew, hh);
      fnow = ++fi < flen ? fAt(fi) : 0.0;
    }
    q = qNew;
    if (hh != 0.0)
      h[hlen++] = hh;
    while (ei < elen && fi < flen)
    {
      if ((fnow > enow) == (fnow > -enow))
      {
        twoSum(q, enow, qNew, hh);
        enow = ++ei < elen ? e[ei] : 0.0;
      }
      else
      {
        twoSum(q, fnow, qNew, hh);
        fnow = ++fi < flen ? fAt(fi) : 0.0;
      }
      q = qNew;
      if (hh != 0.0)
        h[hlen++] = hh;
    }
  }
  while (ei < elen)
  {
    twoSum(q, enow, qNew, hh);
    enow = ++ei < elen ? e[ei] : 0.0;
    q = qNew;
    if (hh != 0.0)
      h[hlen++] = hh;
  }
  while (fi < flen)
  {
    twoSum(q, fnow, qNew, hh);
    fnow = ++fi < flen ? fAt(fi) : 0.0;
    q = qNew;
    if (hh != 0.0)
      h[hlen++] = hh;
  }
  if (q != 0.0 || hlen == 0)
    h[hlen++] = q;
  return hlen;
}

} // namespace

int sumExpansions(int elen, const double* e, int flen, const double* f, double* h)
{
  return mergeSum<false>(elen, e, flen, f, h);
}

int diffExpansions(int elen, const double* e, int flen, const double* f, double* h)
{
  return mergeSum<true>(elen, e, flen, f, h);
}

int multiplyExpansions(int elen,
  const double* e,
  int flen,
  const double* f,
  double* h,
  double* scratch)
{
  // Sum over the components of the shorter factor of (longer factor * component).
  if (elen < flen)
  {
    const double* t = e;
    e = f;
    f = t;
    int tl = elen;
    elen = flen;
    flen = tl;
  }
  double* term = scratch;           // 2*elen
  double* acc = scratch + 2 * elen; // running sum, alternates with h
  int hlen = 0;
  double* cur = h;
  double* other = acc;
  for (int i = 0; i < flen; ++i)
  {
    int tlen = scaleExpansion(elen, e, f[i], term);
    int nlen = sumExpansions(hlen, cur, tlen, term, other);
    double* t = cur;
    cur = other;
    other = t;
    hlen = nlen;
  }
  if (cur != h)
    for (int k = 0; k < hlen; ++k)
      h[k] = cur[k];
  if (hlen == 0)
  {
    h[0] = 0.0;
    hlen = 1;
  }
  return hlen;
}

} // namespace expansion
} // namespace tetmesher
