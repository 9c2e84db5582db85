// Exact predicates against an independent exact oracle (GMP rationals): random input,
// near-degenerate input perturbed by single ulps, exactly degenerate input (coplanar,
// cospherical, grids), and the consistency of the symbolic perturbation.
#include "ExpansionArithmetic.h"
#include "FilteredPredicates.h"
#include "Predicates.h"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

using namespace tetmesher;
using Point = std::array<double, 3>;

namespace
{

int signOf(const mpq_class& x)
{
  return mpq_sgn(x.get_mpq_t());
}

mpq_class det3(const mpq_class m[3][3])
{
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
    m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
    m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// det[a-d; b-d; c-d]
int oracleOrient3d(const Point& a, const Point& b, const Point& c, const Point& d)
{
  const Point* p[3] = { &a, &b, &c };
  mpq_class m[3][3];
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      m[r][k] = mpq_class((*p[r])[k]) - mpq_class(d[k]);
  return signOf(det3(m));
}

// Insphere as a 4x4 determinant of rows (p - e, |p - e|^2 + lift perturbation), expanded by
// the last column; positive when e is inside the sphere of a positive (a,b,c,d).
int oracleInsphere(const std::array<Point, 5>& p, const std::array<mpq_class, 5>& delta)
{
  mpq_class m[4][4];
  for (int r = 0; r < 4; ++r)
  {
    mpq_class lift = 0;
    for (int k = 0; k < 3; ++k)
    {
      m[r][k] = mpq_class(p[r][k]) - mpq_class(p[4][k]);
      lift += m[r][k] * m[r][k];
    }
    m[r][3] = lift + delta[r] - delta[4];
  }
  mpq_class det = 0;
  for (int r = 0; r < 4; ++r)
  {
    mpq_class minor[3][3];
    for (int i = 0, mi = 0; i < 4; ++i)
    {
      if (i == r)
        continue;
      for (int k = 0; k < 3; ++k)
        minor[mi][k] = m[i][k];
      ++mi;
    }
    // cofactor sign of entry (r,3): (-1)^(r+3)
    const mpq_class term = m[r][3] * det3(minor);
    det += ((r + 3) % 2 == 0) ? term : mpq_class(-term);
  }
  // With Shewchuk's orientation convention, det[p-e, lift] > 0 means e inside.
  return signOf(det);
}

int oracleInsphere(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e)
{
  std::array<mpq_class, 5> zero;
  for (auto& z : zero)
    z = 0;
  return oracleInsphere({ a, b, c, d, e }, zero);
}

int oracleOrient2d(const Point& a, const Point& b, const Point& c, int drop)
{
  const int i = (drop + 1) % 3, j = (drop + 2) % 3;
  mpq_class l = (mpq_class(a[i]) - c[i]) * (mpq_class(b[j]) - c[j]);
  mpq_class r = (mpq_class(a[j]) - c[j]) * (mpq_class(b[i]) - c[i]);
  return signOf(mpq_class(l - r));
}

struct Random
{
  std::mt19937_64 gen{ 12345 };
  double uniform(double lo, double hi)
  {
    return std::uniform_real_distribution<double>(lo, hi)(gen);
  }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(gen); }
  Point point(double lo = -1, double hi = 1)
  {
    return { uniform(lo, hi), uniform(lo, hi), uniform(lo, hi) };
  }
  // Moves a random coordinate by up to `ulps` units in the last place.
  Point nudge(Point p, int ulps)
  {
    int k = integer(0, 2);
    int steps = integer(-ulps, ulps);
    for (int s = 0; s < std::abs(steps); ++s)
      p[k] = std::nextafter(p[k], steps > 0 ? INFINITY : -INFINITY);
    return p;
  }
};

void expectOrient3d(const Point& a, const Point& b, const Point& c, const Point& d)
{
  ASSERT_EQ(
    predicates::orient3d(a.data(), b.data(), c.data(), d.data()), oracleOrient3d(a, b, c, d))
    << a[0] << " " << a[1] << " " << a[2] << " | " << d[0] << " " << d[1] << " " << d[2];
}

void expectInsphere(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e)
{
  ASSERT_EQ(predicates::insphere(a.data(), b.data(), c.data(), d.data(), e.data()),
    oracleInsphere(a, b, c, d, e));
}

// Integer points on the sphere x^2+y^2+z^2 = 25 (and a few more radii): exactly cospherical.
std::vector<Point> integerSpherePoints(int r2)
{
  std::vector<Point> pts;
  for (int x = -7; x <= 7; ++x)
    for (int y = -7; y <= 7; ++y)
      for (int z = -7; z <= 7; ++z)
        if (x * x + y * y + z * z == r2)
          pts.push_back({ double(x), double(y), double(z) });
  return pts;
}

} // namespace

TEST(ExpansionArithmetic, TwoProductAndSumAreExact)
{
  Random rnd;
  for (int i = 0; i < 10000; ++i)
  {
    double a = rnd.uniform(-1e10, 1e10), b = rnd.uniform(-1e-5, 1e-5), x, y;
    expansion::twoProduct(a, b, x, y);
    EXPECT_EQ(mpq_class(x) + mpq_class(y), mpq_class(a) * mpq_class(b));
    expansion::twoSum(a, b, x, y);
    EXPECT_EQ(mpq_class(x) + mpq_class(y), mpq_class(a) + mpq_class(b));
    expansion::twoDiff(a, b, x, y);
    EXPECT_EQ(mpq_class(x) + mpq_class(y), mpq_class(a) - mpq_class(b));
  }
}

TEST(ExpansionArithmetic, ProductsAndSumsOfExpansions)
{
  Random rnd;
  for (int i = 0; i < 2000; ++i)
  {
    // Build two expansions as exact sums of random doubles of wildly different magnitudes.
    double e[8], f[8], h[256], scratch[512];
    int elen = 0, flen = 0;
    mpq_class ev = 0, fv = 0;
    for (int k = 0; k < 4; ++k)
    {
      double x = std::ldexp(rnd.uniform(-1, 1), rnd.integer(-60, 60));
      double tmp[16];
      double one[1] = { x };
      elen = expansion::sumExpansions(elen, e, 1, one, tmp);
      std::copy(tmp, tmp + elen, e);
      ev += x;
      double yv = std::ldexp(rnd.uniform(-1, 1), rnd.integer(-60, 60));
      double one2[1] = { yv };
      flen = expansion::sumExpansions(flen, f, 1, one2, tmp);
      std::copy(tmp, tmp + flen, f);
      fv += yv;
    }
    auto value = [](const double* x, int n)
    {
      mpq_class s = 0;
      for (int k = 0; k < n; ++k)
        s += x[k];
      return s;
    };
    ASSERT_EQ(value(e, elen), ev);
    int hlen = expansion::multiplyExpansions(elen, e, flen, f, h, scratch);
    ASSERT_EQ(value(h, hlen), ev * fv);
    ASSERT_EQ(expansion::expansionSign(hlen, h), signOf(mpq_class(ev * fv)));
    hlen = expansion::diffExpansions(elen, e, flen, f, h);
    ASSERT_EQ(value(h, hlen), ev - fv);
  }
}

TEST(Predicates, RandomInputMatchesOracle)
{
  Random rnd;
  for (int i = 0; i < 20000; ++i)
  {
    Point a = rnd.point(), b = rnd.point(), c = rnd.point(), d = rnd.point(), e = rnd.point();
    expectOrient3d(a, b, c, d);
    expectInsphere(a, b, c, d, e);
    for (int drop = 0; drop < 3; ++drop)
      ASSERT_EQ(
        predicates::orient2d(a.data(), b.data(), c.data(), drop), oracleOrient2d(a, b, c, drop));
  }
}

TEST(Predicates, NearlyCoplanarPerturbedByUlps)
{
  Random rnd;
  for (int i = 0; i < 50000; ++i)
  {
    const double scale = std::ldexp(1.0, rnd.integer(-40, 40));
    const double shift = rnd.uniform(-1000, 1000) * scale;
    Point a = rnd.point(), b = rnd.point(), c = rnd.point();
    for (Point* p : { &a, &b, &c })
      for (double& x : *p)
        x = x * scale + shift;
    const double s = rnd.uniform(-2, 2), t = rnd.uniform(-2, 2);
    Point d;
    for (int k = 0; k < 3; ++k)
      d[k] = a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]);
    d = rnd.nudge(d, 2);
    expectOrient3d(a, b, c, d);
    expectOrient3d(d, a, b, c);
    for (int drop = 0; drop < 3; ++drop)
    {
      Point e = b;
      const int i2 = (drop + 1) % 3, j2 = (drop + 2) % 3;
      const double u = rnd.uniform(-2, 2);
      e[i2] = a[i2] + u * (c[i2] - a[i2]);
      e[j2] = a[j2] + u * (c[j2] - a[j2]);
      e = rnd.nudge(e, 1);
      ASSERT_EQ(
        predicates::orient2d(a.data(), e.data(), c.data(), drop), oracleOrient2d(a, e, c, drop));
    }
  }
}

// orient3dExact answers from a memo keyed by the sorted points (Predicates.cxx): every order
// of the same four points, asked again after hits and after evictions (more point sets than
// the table's 4096 slots), must give the oracle's sign. Exactly coplanar sets (on planes no
// axis is normal to, dyadic so the points are exact), sets an ulp off, and duplicated points.
TEST(Predicates, Orient3dExactInEveryOrderAndAgain)
{
  Random rnd;
  std::vector<std::array<Point, 4>> sets;
  for (int i = 0; i < 6000; ++i)
  {
    std::array<Point, 4> q;
    const double ca = rnd.integer(-8, 8) / 4.0, cb = rnd.integer(-8, 8) / 4.0;
    for (Point& p : q)
    {
      p[0] = rnd.integer(-64, 64) / 8.0;
      p[1] = rnd.integer(-64, 64) / 8.0;
      p[2] = ca * p[0] + cb * p[1] + 0.5;
    }
    if (i % 3 == 1)
      q[3] = rnd.nudge(q[3], 1);
    if (i % 7 == 0)
      q[2] = q[0];
    sets.push_back(q);
  }
  std::array<int, 4> order = { 0, 1, 2, 3 };
  for (int round = 0; round < 2; ++round)
  {
    for (const auto& q : sets)
    {
      std::sort(order.begin(), order.end());
      do
      {
        const Point &a = q[order[0]], &b = q[order[1]], &c = q[order[2]], &d = q[order[3]];
        ASSERT_EQ(predicates::orient3dExact(a.data(), b.data(), c.data(), d.data()),
          oracleOrient3d(a, b, c, d));
      } while (std::next_permutation(order.begin(), order.end()));
    }
  }
}

TEST(Predicates, NearlyCosphericalPerturbedByUlps)
{
  Random rnd;
  for (int i = 0; i < 20000; ++i)
  {
    // Points on a sphere computed in floating point: cospherical up to rounding.
    const double radius = std::ldexp(rnd.uniform(0.5, 1), rnd.integer(-20, 20));
    const Point center = rnd.point(-100, 100);
    std::array<Point, 5> p;
    for (Point& q : p)
    {
      Point dir = rnd.point();
      double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
      for (int k = 0; k < 3; ++k)
        q[k] = center[k] + radius * dir[k] / len;
    }
    p[4] = rnd.nudge(p[4], 3);
    expectInsphere(p[0], p[1], p[2], p[3], p[4]);
    expectInsphere(p[4], p[0], p[1], p[2], p[3]);
  }
}

// Points on the unit sphere about the origin, as tessellated spheres have them (coordinates
// in [-1, 1], some near 0): beyond the double and extended filters, decided by the stage on
// integer coordinates (one limb; two with a coordinate of 6e-17 among them); with one of
// 1e-30 the span is too wide for it and the expansions decide. Also nearly coplanar points of
// such spheres (orient3d), and subnormal coordinates, which the lattice stage must decline.
TEST(Predicates, UnitSphereAndWideSpans)
{
  Random rnd;
  auto onSphere = [&rnd]()
  {
    Point dir = rnd.point();
    const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    for (double& x : dir)
      x /= len;
    return dir;
  };
  for (int i = 0; i < 20000; ++i)
  {
    std::array<Point, 5> p;
    for (Point& q : p)
      q = onSphere();
    if (i % 4 == 1)
      p[rnd.integer(0, 4)][rnd.integer(0, 2)] = 1e-30; // span too wide for 61 bits
    if (i % 4 == 2)
      p[4] = p[rnd.integer(0, 3)]; // a repeated point: exactly zero
    if (i % 4 == 3)
      p[rnd.integer(0, 4)][rnd.integer(0, 2)] = std::cos(M_PI / 2); // 6e-17: ~106 bits
    p[4] = rnd.nudge(p[4], 2);
    expectInsphere(p[0], p[1], p[2], p[3], p[4]);
    expectInsphere(p[4], p[3], p[2], p[1], p[0]);
    // Three points on a great circle and a fourth nearly on its plane.
    Point a = onSphere(), b = onSphere();
    Point c = { -a[0], -a[1], -a[2] };
    const double t = rnd.uniform(-1, 1);
    Point d = { t * a[0] + (1 - t) * b[0], t * a[1] + (1 - t) * b[1], t * a[2] + (1 - t) * b[2] };
    d = rnd.nudge(d, 2);
    if (i % 2 == 1)
      d[rnd.integer(0, 2)] = std::cos(M_PI / 2);
    expectOrient3d(a, b, c, d);
    expectOrient3d(d, c, b, a);
  }
  // Subnormal coordinates: differences of a few bits whose scaling 2^1074 is no double.
  for (int i = 0; i < 2000; ++i)
  {
    auto tiny = [&rnd]()
    {
      return Point{
        rnd.integer(-8, 8) * 5e-324, rnd.integer(-8, 8) * 5e-324, rnd.integer(-8, 8) * 5e-324
      };
    };
    const Point a = tiny(), b = tiny(), c = tiny(), d = tiny(), e = tiny();
    expectOrient3d(a, b, c, d);
    expectInsphere(a, b, c, d, e);
  }
}

// insphereTerms evaluates in vector lanes what insphereTermsScalar evaluates one operation at
// a time: det, the permanent and the cofactors must be the same doubles for every input (a zero's
// sign aside, which no comparison sees; NaN where the scalar has NaN), so that the filter answers
// the same and the meshes do not depend on which one runs. Random, nearly co-spherical, repeated,
// subnormal and huge (overflowing) points.
TEST(Predicates, VectorInsphereTermsAreTheScalarOnes)
{
  Random rnd;
  auto same = [](double x, double y) { return x == y || (std::isnan(x) && std::isnan(y)); };
  int undecided = 0;
  for (int i = 0; i < 400000; ++i)
  {
    std::array<Point, 5> p;
    const int kind = i % 5;
    const double scale = std::ldexp(1.0, rnd.integer(-60, 60));
    for (Point& q : p)
    {
      q = rnd.point();
      if (kind == 1) // on a sphere, up to rounding
      {
        const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        for (double& x : q)
          x /= len;
      }
      for (double& x : q)
        x *= kind == 3 ? 5e-324 * rnd.integer(-8, 8) : kind == 4 ? 1e300 : scale;
    }
    if (kind == 2)
      p[4] = p[rnd.integer(0, 3)];
    p[4] = rnd.nudge(p[4], 2);
    const predicates::InsphereTerms vector =
      predicates::insphereTerms(p[0].data(), p[1].data(), p[2].data(), p[3].data(), p[4].data());
    const predicates::InsphereTerms scalar = predicates::insphereTermsScalar(
      p[0].data(), p[1].data(), p[2].data(), p[3].data(), p[4].data());
    ASSERT_TRUE(same(vector.det, scalar.det))
      << "case " << i << ": " << vector.det << " against " << scalar.det;
    ASSERT_TRUE(same(vector.permanent, scalar.permanent))
      << "case " << i << ": " << vector.permanent << " against " << scalar.permanent;
    for (int k = 0; k < 4; ++k)
      ASSERT_TRUE(same(vector.cofactor[k], scalar.cofactor[k]))
        << "case " << i << ", cofactor " << k;
    undecided += predicates::insphereFilterSign(scalar) == predicates::kUndecided;
  }
  // The near-degenerate kinds reach the undecided answer too.
  EXPECT_GT(undecided, 1000);
}

TEST(Predicates, ExactlyDegenerateIntegerInput)
{
  Random rnd;
  // Cospherical: integer points of a sphere, shifted by large exact offsets and scaled by
  // powers of two (both exact in doubles).
  for (int r2 : { 25, 49, 50 })
  {
    std::vector<Point> sphere = integerSpherePoints(r2);
    ASSERT_GE(sphere.size(), 5u);
    for (int i = 0; i < 3000; ++i)
    {
      const double scale = std::ldexp(1.0, rnd.integer(-30, 30));
      const double shift = std::ldexp(double(rnd.integer(-1000, 1000)), rnd.integer(0, 20));
      std::array<Point, 5> p;
      for (Point& q : p)
      {
        q = sphere[rnd.integer(0, int(sphere.size()) - 1)];
        for (double& x : q)
          x = x * scale + shift * scale;
      }
      expectOrient3d(p[0], p[1], p[2], p[3]);
      expectInsphere(p[0], p[1], p[2], p[3], p[4]);
      if (oracleOrient3d(p[0], p[1], p[2], p[3]) != 0)
      {
        EXPECT_EQ(
          predicates::insphere(p[0].data(), p[1].data(), p[2].data(), p[3].data(), p[4].data()), 0);
      }
    }
  }
  // Grid points: coplanar and cospherical everywhere.
  for (int i = 0; i < 20000; ++i)
  {
    std::array<Point, 5> p;
    for (Point& q : p)
      q = { double(rnd.integer(0, 3)), double(rnd.integer(0, 3)), double(rnd.integer(0, 3)) };
    expectOrient3d(p[0], p[1], p[2], p[3]);
    expectInsphere(p[0], p[1], p[2], p[3], p[4]);
    ASSERT_EQ(predicates::orient2d(p[0].data(), p[1].data(), p[2].data(), 2),
      oracleOrient2d(p[0], p[1], p[2], 2));
  }
}

// Integer differences too wide for the 64-bit stage (11 bits) but within the 128-bit one's
// 24 bits, as on the refinement's snapped lattice (odd steps of 2^11 units and more):
// exactly co-spherical tuples must give 0, up to the top of the range (differences of
// 14 * 2^20 units; an overflow would give a sign), and one unit off the sphere a sign.
// (Non-zero values this wide are decided by the filter before the integer stages.)
TEST(Predicates, WideIntegerInput)
{
  Random rnd;
  for (int r2 : { 25, 50 })
  {
    std::vector<Point> sphere = integerSpherePoints(r2);
    for (int i = 0; i < 5000; ++i)
    {
      const double step = 2 * rnd.integer(1 << 10, (1 << 19) - 1) + 1; // odd, 2^11..2^20
      const double unit = std::ldexp(1.0, rnd.integer(-40, 0));
      const double origin = std::ldexp(double(rnd.integer(-(1 << 20), 1 << 20)), 12);
      std::array<Point, 5> p;
      for (Point& q : p)
      {
        q = sphere[rnd.integer(0, int(sphere.size()) - 1)];
        for (double& x : q)
          x = (origin + x * step) * unit;
      }
      expectInsphere(p[0], p[1], p[2], p[3], p[4]);
      if (oracleOrient3d(p[0], p[1], p[2], p[3]) != 0)
      {
        EXPECT_EQ(
          predicates::insphere(p[0].data(), p[1].data(), p[2].data(), p[3].data(), p[4].data()), 0);
      }
      p[4][rnd.integer(0, 2)] += unit * (rnd.integer(0, 1) ? 1 : -1);
      expectInsphere(p[0], p[1], p[2], p[3], p[4]);
    }
  }
}

TEST(Predicates, ConventionsOnKnownConfigurations)
{
  const Point a{ 1, 0, 0 }, b{ 0, 1, 0 }, c{ 0, 0, 0 }, below{ 0, 0, -1 }, above{ 0, 0, 1 };
  EXPECT_EQ(predicates::orient3d(a.data(), b.data(), c.data(), below.data()), 1);
  EXPECT_EQ(predicates::orient3d(a.data(), b.data(), c.data(), above.data()), -1);
  const Point inside{ 0.2, 0.2, -0.2 }, far{ 10, 10, 10 };
  EXPECT_EQ(predicates::insphere(a.data(), b.data(), c.data(), below.data(), inside.data()), 1);
  EXPECT_EQ(predicates::insphere(a.data(), b.data(), c.data(), below.data(), far.data()), -1);
  EXPECT_EQ(predicates::orient2d(a.data(), b.data(), c.data(), 2), 1);
}

namespace
{

// insphereSoS through a tiny mesh holding the five points with the given ids.
int sosOf(const std::array<Point, 5>& p, const std::array<VertexId, 5>& ids)
{
  TetMesh mesh;
  VertexId maxId = *std::max_element(ids.begin(), ids.end());
  mesh.coords.assign(3 * static_cast<std::size_t>(maxId + 1), 0.0);
  for (int i = 0; i < 5; ++i)
    for (int k = 0; k < 3; ++k)
      mesh.coords[3 * static_cast<std::size_t>(ids[i]) + k] = p[i][k];
  return predicates::insphereSoS(mesh, ids[0], ids[1], ids[2], ids[3], ids[4]);
}

int permutationSign(const std::array<int, 5>& perm)
{
  int inversions = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = i + 1; j < 5; ++j)
      inversions += perm[i] > perm[j];
  return inversions % 2 ? -1 : 1;
}

} // namespace

TEST(Predicates, SymbolicPerturbationMatchesPerturbedOracle)
{
  // The documented rule: lift of vertex i is |p_i|^2 + eps^(K - i), eps -> 0+.
  // The oracle evaluates that determinant with a concrete tiny eps in rational arithmetic.
  Random rnd;
  const std::vector<Point> sphere = integerSpherePoints(25);
  const mpq_class eps = mpq_class(1, 1) / mpq_class(mpz_class(1) << 64);
  const int K = 12;
  int checked = 0;
  for (int i = 0; i < 4000; ++i)
  {
    std::array<Point, 5> p;
    std::array<VertexId, 5> ids;
    std::vector<int> pick;
    while (pick.size() < 5)
    {
      int k = rnd.integer(0, int(sphere.size()) - 1);
      if (std::find(pick.begin(), pick.end(), k) == pick.end())
        pick.push_back(k);
    }
    std::vector<VertexId> idPool = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10 };
    for (int k = 0; k < 5; ++k)
    {
      p[k] = sphere[pick[k]];
      std::swap(idPool[k], idPool[rnd.integer(k, 10)]);
      ids[k] = idPool[k];
    }
    if (oracleOrient3d(p[0], p[1], p[2], p[3]) == 0)
      continue;
    if (oracleOrient3d(p[0], p[1], p[2], p[3]) < 0)
    {
      std::swap(p[0], p[1]);
      std::swap(ids[0], ids[1]);
    }
    std::array<mpq_class, 5> delta;
    for (int k = 0; k < 5; ++k)
    {
      delta[k] = 1;
      for (int j = 0; j < K - ids[k]; ++j)
        delta[k] *= eps;
    }
    const int expected = oracleInsphere(p, delta);
    ASSERT_NE(expected, 0);
    ASSERT_EQ(sosOf(p, ids), expected) << "case " << i;
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

TEST(Predicates, SymbolicPerturbationIsAlternatingAndNeverZero)
{
  Random rnd;
  const std::vector<Point> sphere = integerSpherePoints(50);
  for (int i = 0; i < 300; ++i)
  {
    std::array<Point, 5> p;
    std::array<VertexId, 5> ids;
    for (int k = 0; k < 5; ++k)
    {
      p[k] = sphere[rnd.integer(0, int(sphere.size()) - 1)];
      ids[k] = 100 + 10 * k + rnd.integer(0, 9);
    }
    bool distinct = true;
    for (int a = 0; a < 5; ++a)
      for (int b = a + 1; b < 5; ++b)
        distinct = distinct && p[a] != p[b];
    if (!distinct)
      continue;
    std::array<int, 5> perm = { 0, 1, 2, 3, 4 };
    int reference = 0;
    do
    {
      std::array<Point, 5> q;
      std::array<VertexId, 5> qi;
      for (int k = 0; k < 5; ++k)
        q[k] = p[perm[k]], qi[k] = ids[perm[k]];
      if (oracleOrient3d(q[0], q[1], q[2], q[3]) == 0)
        continue;
      const int s = sosOf(q, qi) * permutationSign(perm);
      ASSERT_NE(s, 0);
      if (reference == 0)
        reference = s;
      ASSERT_EQ(s, reference) << "case " << i;
    } while (std::next_permutation(perm.begin(), perm.end()));
  }
}

// The exact stages with the symbolic perturbation (insphereExactSoS: the integer stages answer
// their own zeros from the determinant's minors) against insphereExact followed by the tie
// break's orientations, on exactly co-spherical points: the corners of boxes (any box's 8
// corners lie on one sphere) whose coordinates take the 64-bit lattice stage (small
// integers), the 128-bit one (integers spanning 12-24 bits), the one-limb and the two-limb
// integer stages (random doubles spanning up to ~53 and ~66 bits), with random ids.
TEST(Predicates, TieBreakFromIntegerMinorsMatchesOrientations)
{
  Random rnd;
  int zeros = 0;
  for (int kind = 0; kind < 4; ++kind)
    for (int i = 0; i < 3000; ++i)
    {
      double lo[3], hi[3];
      for (int k = 0; k < 3; ++k)
      {
        switch (kind)
        {
          case 0:
            lo[k] = rnd.integer(-20, 20);
            hi[k] = lo[k] + rnd.integer(1, 20);
            break;
          case 1:
            lo[k] = rnd.integer(-5, 5);
            hi[k] = lo[k] + rnd.integer(1, 3) * 4096.0 + rnd.integer(0, 7);
            break;
          case 2:
            lo[k] = rnd.uniform(-1, 1);
            hi[k] = lo[k] + rnd.uniform(0.01, 1);
            break;
          default:
            lo[k] = std::ldexp(rnd.uniform(-1, 1), -12);
            hi[k] = rnd.uniform(1, 8);
        }
      }
      std::array<Point, 8> corner;
      for (int c = 0; c < 8; ++c)
        corner[c] = { (c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2] };
      std::array<int, 8> pick = { 0, 1, 2, 3, 4, 5, 6, 7 };
      for (int k = 0; k < 5; ++k)
        std::swap(pick[k], pick[rnd.integer(k, 7)]);
      const double* p[5];
      VertexId ids[5];
      for (int k = 0; k < 5; ++k)
      {
        p[k] = corner[pick[k]].data();
        ids[k] = static_cast<VertexId>(rnd.integer(0, 1000) * 5 + k); // distinct
      }
      const int o = predicates::orient3d(p[0], p[1], p[2], p[3]);
      if (o == 0)
        continue;
      if (o < 0)
      {
        std::swap(p[0], p[1]);
        std::swap(ids[0], ids[1]);
      }
      const int exact = predicates::insphereExact(p[0], p[1], p[2], p[3], p[4]);
      zeros += exact == 0;
      const int expected = exact != 0 ? exact : predicates::insphereTieBreak(p, ids);
      ASSERT_NE(expected, 0);
      ASSERT_EQ(predicates::insphereExactSoS(p, ids), expected) << "kind " << kind << " #" << i;
    }
  EXPECT_GT(zeros, 4000); // the tie break was exercised, not only non-zero determinants
}
